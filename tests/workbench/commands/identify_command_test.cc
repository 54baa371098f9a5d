// RunIdentify's control (IdentifyControl): progress over a whole run is
// non-decreasing and reaches 1; a stop set from the progress callback ends
// the run with IdentifyStatus::kCancelled and nothing written; a run with a
// control identifies exactly as one without.
#include "idbench/workbench/commands/identify_command.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <unistd.h>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

// A puma560 log of 30 s at 1 kHz (t, q, qd, qdd, τ): ~4 streaming blocks per
// pass, held out on itself, so a run has 5 stages (2 reads, 2 folds, the solve).
class IdentifyCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_identify_command_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 30.0});
    const JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(30001, 0.0, 30.0));
    options_.data = options_.validate = (dir_ / "log.csv").string();
    std::ofstream(options_.data) << FormatJointLogCsv(log);
    options_.friction = {"viscous", "coulomb"};
    options_.estimator = TorqueEstimator::kOls;
    options_.out_dir = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  RobotModel model_ = MakePuma560();
  IdentifyOptions options_;
  fs::path dir_;
};

TEST_F(IdentifyCommandTest, ProgressIsMonotoneAndReachesOne) {
  std::vector<IdentifyProgress> reports;
  IdentifyControl control;
  control.progress = [&](const IdentifyProgress& p) { reports.push_back(p); };
  const IdentifyReport report = RunIdentify(model_, options_, control);
  ASSERT_EQ(report.status, IdentifyStatus::kDone);
  ASSERT_FALSE(reports.empty());
  for (size_t k = 1; k < reports.size(); ++k) EXPECT_GE(reports[k].fraction, reports[k - 1].fraction) << k;
  EXPECT_GE(reports.front().fraction, 0.0);
  EXPECT_EQ(reports.back().fraction, 1.0);
  EXPECT_EQ(reports.back().stage, "done");
  // Reported within the passes too: every stage start (k/5) and blocks between.
  int inside = 0;
  for (const IdentifyProgress& p : reports) inside += p.fraction > 0.0 && p.fraction < 1.0 && p.fraction * 5 != std::round(p.fraction * 5);
  EXPECT_GE(inside, 8);
  // The same numbers as a run without a control.
  const IdentifyReport plain = RunIdentify(model_, options_);
  EXPECT_EQ(report.identification.beta, plain.identification.beta);
  EXPECT_EQ(report.validation->relative_error, plain.validation->relative_error);
}

TEST_F(IdentifyCommandTest, StopFromTheProgressCallbackCancels) {
  std::atomic<bool> stop{false};
  double stopped_at = -1.0, last = -1.0;
  IdentifyControl control;
  control.stop = &stop;
  control.progress = [&](const IdentifyProgress& p) {
    last = p.fraction;
    if (p.fraction >= 0.3 && !stop) {
      stop = true;
      stopped_at = p.fraction;
    }
  };
  const IdentifyReport report = RunIdentify(model_, options_, control);
  EXPECT_EQ(report.status, IdentifyStatus::kCancelled);
  EXPECT_GE(stopped_at, 0.3);
  EXPECT_EQ(last, stopped_at);  // nothing reported once stopped
  EXPECT_EQ(report.n_samples, 0);
  EXPECT_FALSE(report.prepared);
  EXPECT_FALSE(fs::exists(options_.out_dir));
  // Stopped before it starts: cancelled at once.
  const IdentifyReport before = RunIdentify(model_, options_, control);
  EXPECT_EQ(before.status, IdentifyStatus::kCancelled);
}

}  // namespace
}  // namespace idbench
