// Runs the `idbench` executable as a user would (path in $IDBENCH).
#include <gtest/gtest.h>

#include "workbench/cli/cli_fixture.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using idbench::testing::Result;
using idbench::testing::Slurp;

// Paper Table 1 (printed to 4 decimals): m, J11, J22 = J33 of B1..B6, the
// independent truth the identified values are checked against.
constexpr double kTable1[6][3] = {
    {6402.6012, 800.3251, 982.8126}, {2746.0726, 123.5733, 416.4934}, {1186.1661, 23.7233, 156.5838},
    {308.7953, 6.1759, 5.6413},      {284.2877, 5.6858, 4.8353},      {661.7042, 29.7767, 19.8511}};

double Table1(int body, const std::string& name) {
  if (name == "J11") return kTable1[body][1];
  if (name == "J22" || name == "J33") return kTable1[body][2];
  return kTable1[body][0];  // m, m_e1, m_e2, m_e3
}

class CliTest : public idbench::testing::CliFixture {
 protected:
  // Checks results.json: every identifiable parameter within tol, B1's
  // m_e1, m_e2, J22, J33 flagged with null values, all others identified.
  void ExpectPaperTables(const fs::path& results, double tol) {
    const nlohmann::json j = nlohmann::json::parse(Slurp(results));
    ASSERT_EQ(j["bodies"].size(), 6u);
    double worst = 0.0;
    int body_index = 0;
    for (const auto& body : j["bodies"]) {
      ASSERT_EQ(body["parameters"].size(), 7u);
      for (const auto& p : body["parameters"]) {
        const std::string name = p["name"];
        const bool expect_flag = body["name"] == "B1" && (name == "m_e1" || name == "m_e2" || name == "J22" || name == "J33");
        EXPECT_EQ(p["identifiable"].get<bool>(), !expect_flag) << body["name"] << "." << name;
        if (expect_flag) {
          EXPECT_TRUE(p["identified"].is_null());
          EXPECT_FALSE(p["reason"].get<std::string>().empty());
          continue;
        }
        const double truth = p["true"], identified = p["identified"];
        // Against the printed table (4 decimals), then against the exact truth.
        EXPECT_NEAR(identified, Table1(body_index, name), 5e-5) << body["name"] << "." << name;
        EXPECT_LT(std::abs(identified - truth) / truth, tol) << body["name"] << "." << name;
        worst = std::max(worst, std::abs(identified - truth) / truth);
      }
      ++body_index;
    }
    EXPECT_NEAR(j["max_rel_error"].get<double>(), worst, 1e-3 * worst + 1e-300);
    EXPECT_LT(j["max_rel_error"].get<double>(), tol);
  }

};

TEST_F(CliTest, DefaultRunReproducesThePaperFarMoreAccurately) {
  const Result r = Run("run --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("NOT IDENTIFIABLE"), std::string::npos);
  EXPECT_NE(r.out.find("largest relative error"), std::string::npos);
  ExpectPaperTables(dir_ / "run" / "results.json", 1e-9);
  const nlohmann::json j = nlohmann::json::parse(Slurp(dir_ / "run" / "results.json"));
  EXPECT_EQ(j["sample_times"], nlohmann::json({0.3, 0.6, 0.9, 1.2, 1.5}));
  // log.csv: a header and one row per step, every row with the header's width.
  std::ifstream log(dir_ / "run" / "log.csv");
  std::string header, line;
  std::getline(log, header);
  EXPECT_EQ(header.rfind("t,q1,q2", 0), 0u);
  const auto width = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(log, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), width) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 2000);
}

TEST_F(CliTest, GeneralMotionAlsoReproducesTheTables) {
  const Result r = Run("run --motion general --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "run" / "results.json", 1e-9);
}

TEST_F(CliTest, AllSamplesAndCustomSampling) {
  Result r = Run("run --all-samples --duration 1 --dt 0.002 --out " + (dir_ / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "a" / "results.json", 1e-9);
  r = Run("run --samples 0.1,0.25,0.5,0.75 --accel 45 --out " + (dir_ / "b").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "b" / "results.json", 1e-9);
}

TEST_F(CliTest, BadUsageNamesTheValueAndExitsWith2) {
  const std::pair<std::string, std::string> cases[] = {
      {"run --dt 0", "--dt"},
      {"run --dt abc", "--dt"},
      {"run --duration -1", "--duration"},
      {"run --accel 0", "--accel"},
      {"run --samples 0.3,2.5", "2.5"},
      {"run --samples 0.3,0.6", "at least 4"},
      {"run --samples 0.3,0.6,0.9,0.3", "given twice"},
      {"run --motion wobble", "wobble"},
      {"run --robot nosuch", "nosuch"},
      {"run --frobnicate", "--frobnicate"},
      {"run --dt 0.1", "stable tracking"},
      {"run --dt 1e-12 --duration 1e-11", "--dt"},
      {"run --duration 1.05 --dt 0.1", "whole number"},
      {"run --samples 0.3,0.6,0.9,0.9005", "step grid"},
      {"run --all-samples --samples 0.3,0.6,0.9,1.2", "excludes"},
      {"run --accel 1e308", "--accel"},
      {"run --samples ,", "--samples"},
      {"--frobnicate", "--frobnicate"},
      {"bogus", "bogus"},
      {"", "subcommand"},
  };
  for (const auto& [args, fragment] : cases) {
    const bool is_run = args.rfind("run", 0) == 0;
    const Result r = Run(is_run ? args + " --out " + (dir_ / "never").string() : args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << " -> " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "never")) << args;
  }
}

TEST_F(CliTest, ExistingOutputDirectoryIsNeverWiped) {
  const fs::path out = dir_ / "mine";
  fs::create_directories(out);
  std::ofstream(out / "notes.txt") << "keep me";
  const Result r = Run("run --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(out / "notes.txt"), "keep me");
  EXPECT_TRUE(fs::exists(out / "results.json"));
  // No temporary files are left behind.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out)) ++entries;
  EXPECT_EQ(entries, 4);  // notes.txt, results.json, log.csv, figure.png
}

TEST_F(CliTest, OutputPathThatIsAFileIsRejectedWithoutTouchingIt) {
  const fs::path file = dir_ / "afile";
  std::ofstream(file) << "precious";
  const Result r = Run("run --out " + file.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << "nothing runs before the options are checked";
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(Slurp(file), "precious");
}

// Issue 12: a vendor URDF with a two-finger prismatic gripper (one finger a
// <mimic>) on the flange, and a link of 0.2 kg with an all-zero inertia:
// simulate loads it with one warning for the fingers and one for that link; --lock and --tip
// change the chain; options that do not fit are refused with the exit codes
// of bad usage (2) and of a file that does not fit (1).
TEST_F(CliTest, VendorUrdfWithGripperAndPointMassLinkLoads) {
  const auto inertial = [](const std::string& mass, const std::string& i) {
    return "<inertial><origin xyz=\"0 0 0.05\"/><mass value=\"" + mass + "\"/><inertia ixx=\"" + i +
           "\" ixy=\"0\" ixz=\"0\" iyy=\"" + i + "\" iyz=\"0\" izz=\"" + i + "\"/></inertial>";
  };
  const auto joint = [](const std::string& name, const std::string& type, const std::string& parent,
                        const std::string& child, const std::string& extra) {
    return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" +
           child + "\"/><origin xyz=\"0 0 0.2\"/>" + extra + "</joint>";
  };
  const std::string limit = "<axis xyz=\"0 1 0\"/><limit lower=\"-2\" upper=\"2\" effort=\"50\" velocity=\"2\"/>";
  const std::string finger = "<limit lower=\"0\" upper=\"0.04\" effort=\"20\" velocity=\"0.2\"/>";
  const std::string urdf =
      "<robot name=\"vendor\"><link name=\"base\"/>"
      "<link name=\"l1\">" + inertial("3", "0.02") + "</link><link name=\"l2\">" + inertial("0.2", "0") +
      "</link><link name=\"flange\">" + inertial("1", "0.005") + "</link><link name=\"hand\">" + inertial("0.5", "0.001") +
      "</link><link name=\"left\">" + inertial("0.02", "1e-6") + "</link><link name=\"right\">" +
      inertial("0.02", "1e-6") + "</link>" + joint("j1", "revolute", "base", "l1", limit) +
      joint("j2", "revolute", "l1", "l2", limit) + joint("j3", "revolute", "l2", "flange", limit) +
      "<joint name=\"tool\" type=\"fixed\"><parent link=\"flange\"/><child link=\"hand\"/></joint>" +
      joint("finger1", "prismatic", "hand", "left", "<axis xyz=\"1 0 0\"/>" + finger) +
      joint("finger2", "prismatic", "hand", "right",
            "<axis xyz=\"-1 0 0\"/>" + finger + "<mimic joint=\"finger1\"/>") +
      "</robot>";
  const fs::path file = dir_ / "vendor.urdf";
  std::ofstream(file) << urdf;
  const std::string simulate = "simulate --robot " + file.string() + " --duration 0.2 --out " + (dir_ / "log.csv").string();

  Result r = Run(simulate);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> warnings;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("idbench: warning: ", 0) == 0) warnings.push_back(line);
  }
  ASSERT_EQ(warnings.size(), 2u) << r.err;
  EXPECT_NE(warnings[0].find("link 'l2': mass 0.2 kg"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("raised to it: 8e-06, 8e-06, 8e-06 kg m²"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("locked 2 joints"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("'finger1' (prismatic, at 0 m, into link 'flange')"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("'finger2' (prismatic, mimics 'finger1', at 0 m, into link 'flange')"), std::string::npos)
      << warnings[1];
  std::string header;
  std::getline(std::ifstream(dir_ / "log.csv") >> std::ws, header);
  EXPECT_EQ(header.rfind("t,q1,q2,q3,qd1,", 0), 0u) << header;

  // --tip l2: j3 is locked too, and the flange, hand and fingers join l2
  // (whose inertia is then positive definite: no inertia warning).
  r = Run(simulate + " --tip l2 --lock finger1=0.02");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("'j3' (revolute, at 0 rad, into link 'l2')"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'finger1' (prismatic, at 0.02 m by --lock, into link 'l2')"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("positive definite"), std::string::npos) << r.err;
  std::getline(std::ifstream(dir_ / "log.csv") >> std::ws, header);
  EXPECT_EQ(header.rfind("t,q1,q2,qd1,", 0), 0u) << header;

  r = Run(simulate + " --lock finger1=0.05");
  EXPECT_EQ(r.exit_code, 2);  // options that do not fit the file
  EXPECT_NE(r.err.find("vendor.urdf: --lock finger1=0.05: outside the <limit>"), std::string::npos) << r.err;
  r = Run(simulate + " --lock wrist=0");
  EXPECT_EQ(r.exit_code, 2);  // options that do not fit the file
  EXPECT_NE(r.err.find("joints that can be locked: 'finger1', 'finger2', 'j1', 'j2', 'j3'"), std::string::npos) << r.err;
  r = Run(simulate + " --lock finger1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("expected JOINT=VALUE"), std::string::npos) << r.err;
  r = Run("simulate --robot puma560 --tip link6 --out " + (dir_ / "p.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("built-in robot 'puma560'"), std::string::npos) << r.err;
}

}  // namespace
