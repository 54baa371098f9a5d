// idbench export, run as a user would: the identified model again from an
// identify run's identified.json, byte for byte what identify wrote, and the
// verdict's rule (refused unless --write-unverified, exit 1 and the reason).
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <nlohmann/json.hpp>

#include "workbench/cli/cli_fixture.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::Result;
using testing::Slurp;

class ExportCliTest : public testing::CliFixture {
 protected:
  // A noise-free 10 s puma560 experiment at 100 Hz, identified into dir_/id.
  void Identify(const std::string& extra = "") {
    const fs::path log = dir_ / "log.csv";
    Result r = Run("simulate --robot puma560 --duration 10 --rate 100 --out " + log.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = Run("identify --robot puma560 --data " + log.string() + " --out " + (dir_ / "id").string() + " " + extra);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::is_regular_file(dir_ / "id" / "identified.xml"));
  }
  std::string Export(const std::string& extra) {
    return "export --robot puma560 --identified " + (dir_ / "id" / "identified.json").string() + " --out " +
           (dir_ / "export").string() + " " + extra;
  }
};

TEST_F(ExportCliTest, GivesTheFilesIdentifyWrote) {
  Identify();
  Result r = Run(Export("--format mjcf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(dir_ / "export" / "identified.xml"), Slurp(dir_ / "id" / "identified.xml"));
  r = Run(Export("--format urdf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(dir_ / "export" / "identified.urdf"), Slurp(dir_ / "id" / "identified.urdf"));
  r = Run(Export("--format yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "wrote " + (dir_ / "export" / "joints.yaml").string() + "\n");
  EXPECT_EQ(Slurp(dir_ / "export" / "joints.yaml"), Slurp(dir_ / "id" / "joints.yaml"));
}

// With drive gains (read from currents) and offsets, joints.yaml carries every
// value: export's from identified.json alone is the same bytes.
TEST_F(ExportCliTest, GivesJointsYamlWithEveryValue) {
  Identify("--friction viscous,coulomb,offset,rotor --write-unverified");
  const Result r = Run(Export("--format yaml --write-unverified"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string yaml = Slurp(dir_ / "export" / "joints.yaml");
  EXPECT_EQ(yaml, Slurp(dir_ / "id" / "joints.yaml"));
  EXPECT_NE(yaml.find("    offset: "), std::string::npos) << yaml;
  EXPECT_EQ(yaml.find("    offset: null"), std::string::npos) << yaml;
}

// With offsets, this log's physically consistent estimate sits on its mass
// and centre-of-mass bounds, 251 % above the OLS cost: not fit to load.
// identify writes it only when asked; so does export, with the same reason.
TEST_F(ExportCliTest, RefusesAModelNotFitToLoadUnlessAsked) {
  Identify("--friction viscous,coulomb,offset --write-unverified");
  const nlohmann::json j = nlohmann::json::parse(Slurp(dir_ / "id" / "identified.json"));
  ASSERT_FALSE(j["verdict"]["fit_to_load"].get<bool>());
  Result r = Run(Export(""));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a robot model (" + j["verdict"]["message"].get<std::string>() + ")"), std::string::npos)
      << r.err;
  // identified.json names the options' fields; the command line spells them as flags.
  const std::string cause = j["verdict"]["cause"].get<std::string>();
  EXPECT_NE(cause.find("fit without them (plausibility.com_in_geometry = false)"), std::string::npos) << cause;
  EXPECT_NE(r.err.find("fit without them (--com-bound none)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(cause.substr(0, cause.find(" (plausibility."))), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("identified.xml is not written (--write-unverified writes it anyway)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "export"));
  r = Run(Export("--write-unverified"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the physically consistent estimate is not a robot model"), std::string::npos) << r.err;
  EXPECT_EQ(Slurp(dir_ / "export" / "identified.xml"), Slurp(dir_ / "id" / "identified.xml"));
}

// identified.json of another robot, or not identify's: a usage error naming the field.
TEST_F(ExportCliTest, RejectsAnotherRobotsFile) {
  Identify();
  Result r = Run("export --robot paper6r --identified " + (dir_ / "id" / "identified.json").string() + " --out " +
                 (dir_ / "export").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("standard_parameters"), std::string::npos) << r.err;
  std::ofstream(dir_ / "other.json") << "{\"friction\": [\"viscous\"]}";
  r = Run("export --identified " + (dir_ / "other.json").string() + " --out " + (dir_ / "export").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("physically_consistent"), std::string::npos) << r.err;
  r = Run(Export("--format sdf"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "idbench: error: --format: expected mjcf, urdf or yaml, got 'sdf'\n");
  EXPECT_FALSE(fs::exists(dir_ / "export"));
}

}  // namespace
}  // namespace idbench
