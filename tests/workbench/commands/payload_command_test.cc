// The payload command's library: options checked with messages naming their
// fields, the summary's verdict deciding what is written.
#include "idbench/workbench/commands/payload_command.h"

#include <gtest/gtest.h>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/single_joint_motion.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

std::string Why(const PayloadOptions& options, const RobotModel* model = nullptr) {
  std::string why;
  EXPECT_FALSE(model ? options.IsValidFor(*model, &why) : options.IsValid(&why));
  return why;
}

TEST(PayloadCommandTest, OptionsAreCheckedByField) {
  PayloadOptions options;
  options.robot = "puma560";
  options.out_dir = ::testing::TempDir();
  EXPECT_EQ(Why(options).rfind("loaded_log:", 0), 0u) << Why(options);
  options.loaded_log = "loaded.csv";
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.unloaded_log = "loaded.csv";
  EXPECT_EQ(Why(options).rfind("unloaded_log:", 0), 0u);
  options.unloaded_log = "";
  options.unloaded_time_window = {0.0, 1.0};
  EXPECT_EQ(Why(options).rfind("unloaded_time_window:", 0), 0u);
  options.unloaded_time_window.clear();
  options.max_relative_sigma = 0.0;
  EXPECT_EQ(Why(options).rfind("max_relative_sigma:", 0), 0u);
  options.max_relative_sigma = 0.1;
  options.max_projection_distance = std::nan("");
  EXPECT_EQ(Why(options).rfind("max_projection_distance:", 0), 0u);
  options.max_projection_distance = 5.0;
  options.friction = {"sticky"};
  EXPECT_EQ(Why(options).rfind("friction:", 0), 0u);
  options.friction = {"viscous"};
  // Against the robot: the link by its URDF name; the estimator gets its index.
  const RobotModel puma = MakePuma560();
  options.payload_link = "tool0";
  EXPECT_NE(Why(options, &puma).find("payload_link: robot 'puma560' has no link 'tool0'"), std::string::npos);
  options.payload_link = "link4";
  EXPECT_TRUE(options.IsValidFor(puma, &why)) << why;
  EXPECT_EQ(options.estimator(puma).link, 3);
  options.payload_link = "";
  EXPECT_EQ(options.estimator(puma).link, 5);
}

// The summary on prepared logs: a good verdict writes both files; a motion
// that leaves terms unseen writes only payload.json, even when forced.
// PUMA 560 carrying 2.5 kg on link6, logged over 10 s at 100 Hz.
struct LoadedPuma {
  RobotModel puma = MakePuma560();
  RobotModel loaded = testing::WithPayload(puma, 2.5, {0.02, -0.03, 0.08},
                                           Eigen::Vector3d(0.02, 0.025, 0.015).asDiagonal());
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
  PayloadOptions options;
  explicit LoadedPuma(const std::string& loaded_log) {
    options.robot = "puma560";
    options.loaded_log = loaded_log;
    options.out_dir = "out";
  }
  JointLog GeneralMotion() const {
    return testing::SyntheticJointLog(loaded, *MakeBuiltinMotion("general", 6, {.duration = 10.0}), t);
  }
};

TEST(PayloadCommandTest, TheVerdictDecidesTheFiles) {
  LoadedPuma c("<loaded>");
  const RobotModel& puma = c.puma;
  const RobotModel& loaded = c.loaded;
  const Eigen::VectorXd& t = c.t;
  PayloadOptions& options = c.options;
  PreparedLog general;
  general.log = c.GeneralMotion();
  const PayloadSummary good = RunPayloadOnLogs(puma, options, general, std::nullopt);
  EXPECT_TRUE(good.good()) << good.message;
  EXPECT_NE(good.BriefReport().find("payload on link 'link6': mass 2.5 kg"), std::string::npos) << good.BriefReport();
  EXPECT_EQ(PayloadFiles(puma, options, good).size(), 2u);

  PreparedLog wrist;
  wrist.log = testing::SyntheticJointLog(
      loaded, testing::SingleJointMotion((Eigen::VectorXd(6) << 0.3, -0.6, 0.4, 0.5, 0.7, 0.0).finished(), 5, 10.0), t);
  options.write_unverified = true;
  const PayloadSummary unseen = RunPayloadOnLogs(puma, options, wrist, std::nullopt);
  EXPECT_EQ(unseen.status, PayloadStatus::kNotIdentifiable);
  EXPECT_FALSE(WritesPayloadUrdf(options, unseen));
  const auto files = PayloadFiles(puma, options, unseen);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].first.filename(), "payload.json");
  EXPECT_NE(FormatPayloadTable(options, unseen).find("Ixx         not ident."), std::string::npos);
}

// A log held as every k-th sample (longer than LogPreparationOptions::
// kMaxHeldSamples) is fitted as held, and the summary says so with the counts.
TEST(PayloadCommandTest, ALogHeldInPartIsSaidToBe) {
  const LoadedPuma c("long.csv");
  const RobotModel& puma = c.puma;
  const PayloadOptions& options = c.options;
  PreparedLog held;
  held.log = c.GeneralMotion();
  held.n_samples = 3003;
  held.log_stride = 3;
  const PayloadSummary summary = RunPayloadOnLogs(puma, options, held, std::nullopt);
  EXPECT_EQ(summary.n_loaded, 1001);
  const std::string table = FormatPayloadTable(options, summary);
  EXPECT_NE(table.find("long.csv: 3003 prepared samples, one in 3 (1001) used for the payload fit (at most 200000 "
                       "held; a time window chooses which part of the log)"),
            std::string::npos)
      << table;
  PreparedLog whole;
  whole.log = held.log;
  whole.n_samples = 1001;
  EXPECT_EQ(FormatPayloadTable(options, RunPayloadOnLogs(puma, options, whole, std::nullopt)).find("prepared samples"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench
