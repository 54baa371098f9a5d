// RunExport as a library call with typed options: from an identification's
// identified.json alone, each format is the text identify's own writer gives
// for that identification (FormatIdentifiedMjcf, FormatIdentifiedUrdf,
// FormatJointDynamicsYaml), and a model not fit to load is refused; the
// brief report says which file, its size and its status.
#include "idbench/workbench/commands/export_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <unistd.h>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/commands/identify_command.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

// A noise-free 10 s puma560 log at 100 Hz, identified with `friction`;
// identified.json written as identify writes it.
class ExportCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_export_command_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  IdentifyReport Identify(const std::vector<std::string>& friction) {
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
    const JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
    identify_.data = (dir_ / "log.csv").string();
    std::ofstream(identify_.data) << FormatJointLogCsv(log);
    identify_.friction = friction;
    identify_.estimator = TorqueEstimator::kPhysicallyConsistent;
    IdentifyReport report = RunIdentify(model_, identify_);
    export_.identified = (dir_ / "identified.json").string();
    std::ofstream(export_.identified) << FormatIdentifiedJson(model_, identify_, report);
    return report;
  }

  RobotModel model_ = MakePuma560();
  IdentifyOptions identify_;
  ExportOptions export_;
  fs::path dir_;
};

TEST_F(ExportCommandTest, EachFormatIsWhatIdentifyWrites) {
  const IdentifyReport report = Identify({"viscous", "coulomb", "rotor"});
  ASSERT_TRUE(WritesRobotModel(identify_, report));
  const struct {
    ExportFormat format;
    std::string file, text;
  } cases[] = {{ExportFormat::kMjcf, "identified.xml", FormatIdentifiedMjcf(model_, identify_, report)},
               {ExportFormat::kUrdf, "identified.urdf", FormatIdentifiedUrdf(model_, identify_, report)},
               {ExportFormat::kYaml, "joints.yaml", FormatJointDynamicsYaml(model_, identify_, report)}};
  for (const auto& c : cases) {
    export_.format = c.format;
    std::string why;
    ASSERT_TRUE(export_.IsValid(&why)) << why;
    EXPECT_EQ(export_.file_name(), c.file);
    const ExportReport exported = RunExport(model_, export_);
    EXPECT_TRUE(exported.fit_to_load);
    EXPECT_TRUE(exported.writes);
    EXPECT_TRUE(exported.refused.empty()) << exported.refused;
    EXPECT_EQ(exported.content, c.text) << c.file;
    EXPECT_EQ(exported.status, ExportStatus::kWritten);
    EXPECT_EQ(exported.BriefReport(), "export of robot 'puma560' from " + export_.identified + ": " + c.file + " (" +
                                          std::to_string(c.text.size()) + " bytes), written");
  }
}

// Offsets on this short log put the estimate on its bounds: not fit to load.
// Refused unless write_unverified; then joints.yaml carries every offset.
TEST_F(ExportCommandTest, RefusesAModelNotFitToLoadUnlessAsked) {
  const IdentifyReport report = Identify({"viscous", "coulomb", "offset"});
  ASSERT_FALSE(WritesRobotModel(identify_, report));
  export_.format = ExportFormat::kYaml;
  ExportReport exported = RunExport(model_, export_);
  EXPECT_FALSE(exported.writes);
  EXPECT_TRUE(exported.content.empty());
  EXPECT_NE(exported.refused.find("joints.yaml is not written (write_unverified writes it anyway)"), std::string::npos)
      << exported.refused;
  EXPECT_EQ(exported.status, ExportStatus::kRefused);
  EXPECT_EQ(exported.BriefReport(),
            "export of robot 'puma560' from " + export_.identified + ": joints.yaml, refused: " + exported.refused);
  export_.write_unverified = identify_.write_unverified = true;
  exported = RunExport(model_, export_);
  ASSERT_TRUE(exported.writes);
  EXPECT_EQ(exported.content, FormatJointDynamicsYaml(model_, identify_, report));
  EXPECT_EQ(exported.content.find("offset: null"), std::string::npos) << exported.content;
  EXPECT_EQ(exported.status, ExportStatus::kWrittenUnverified);
  EXPECT_EQ(exported.BriefReport(), "export of robot 'puma560' from " + export_.identified + ": joints.yaml (" +
                                        std::to_string(FormatJointDynamicsYaml(model_, identify_, report).size()) +
                                        " bytes), written unverified: " + exported.refused);
}

// identified.json is read as every JSON input is (json_input.h, issue 35
// items 3 and 9): a repeated key (1c4dd0f kept the last) and deep nesting
// are refused naming the file and the key path.
TEST_F(ExportCommandTest, RepeatedKeysAndDeepNestingAreRefused) {
  export_.identified = (dir_ / "identified.json").string();
  const auto refusal = [&](const std::string& text) {
    std::ofstream(export_.identified) << text;
    try {
      RunExport(model_, export_);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no std::invalid_argument");
  };
  EXPECT_EQ(refusal(R"({"friction": ["viscous"], "friction": []})"),
            export_.identified + ": .friction: key repeated in one object (each key may be given once)");
  const std::string deep = refusal("{\"friction\": " + std::string(100'000, '[') + std::string(100'000, ']') + "}");
  EXPECT_EQ(deep.rfind(export_.identified + ": .friction[0][0]", 0), 0u) << deep;
}

}  // namespace
}  // namespace idbench
