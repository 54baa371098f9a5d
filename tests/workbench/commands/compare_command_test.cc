// compare on recorded logs: a noise-free log written from a built-in motion
// (inverse dynamics, ident/synthetic_log.h) has the identifiability of the
// motion it came from, whatever its rate; a log without qd/qdd goes through
// identify's zero-phase filter; a recorded log is ranked with the designed
// motions and not simulated.
#include "idbench/workbench/commands/compare_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "ident/synthetic_log.h"
#include "workbench/cli/joint_log_writer.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class CompareCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_compare_command_test_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    options_.out_dir = (dir_ / "out").string();
    options_.trials = 2;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The built-in "general" motion (as compare builds it) sampled at `t`,
  // written as CSV with the given signals.
  std::string WriteLog(const std::string& name, const Eigen::VectorXd& t, const std::vector<std::string>& signals) {
    const std::unique_ptr<Trajectory> motion =
        MakeBuiltinMotion("general", 6, {.duration = options_.duration, .paper_qdd = 0.5});
    const fs::path path = dir_ / name;
    std::ofstream(path) << testing::JointLogCsvText(testing::SyntheticJointLog(model_, *motion, t), signals, true);
    return path.string();
  }

  RobotModel model_ = MakePuma560();
  CompareOptions options_;
  fs::path dir_;
};

// At 1 kHz the compare instants (every 40 ms over 10 s) are recorded samples:
// the log's cond, log det and σ_min equal the motion's to 1e-6 (measured:
// 4156.94182086 both; %σ of the first parameter 0.2285 vs 0.2286 from 2 trials).
TEST_F(CompareCommandTest, NoiseFreeLogHasTheConditionOfItsMotion) {
  options_.trajectories = {"general"};
  options_.logs = {WriteLog("general.csv", Eigen::VectorXd::LinSpaced(10001, 0.0, 10.0), {"t", "q", "qd", "qdd", "tau"})};
  const CompareReport report = RunCompare(model_, options_);
  ASSERT_EQ(report.motions.size(), 2u);
  const MotionComparison& designed = report.motions[0];
  const MotionComparison& recorded = report.motions[1];
  EXPECT_FALSE(designed.recorded);
  EXPECT_TRUE(recorded.recorded);
  EXPECT_EQ(recorded.duration, 10.0);
  EXPECT_NEAR(recorded.designed.cond / designed.designed.cond, 1.0, 1e-6);
  EXPECT_NEAR(recorded.designed.log_det, designed.designed.log_det, 1e-6);
  EXPECT_NEAR(recorded.designed.sigma_min / designed.designed.sigma_min, 1.0, 1e-6);
  // Not simulated; %σ from the recorded states, within 25 % of the designed
  // motion's (there the mean WLS σ over 2 noisy trials on Bullet's states).
  EXPECT_TRUE(std::isnan(recorded.realised.cond));
  EXPECT_TRUE(std::isnan(recorded.mean_relative_error));
  EXPECT_FALSE(std::isnan(designed.mean_relative_error));
  ASSERT_EQ(recorded.predicted_sigma.size(), designed.predicted_sigma.size());
  for (Eigen::Index k = 0; k < recorded.predicted_sigma.size(); ++k) {
    EXPECT_NEAR(recorded.predicted_sigma[k] / designed.predicted_sigma[k], 1.0, 0.25) << report.parameter_names[k];
  }
  // Equal cond: both ranked, 1 and 2.
  EXPECT_EQ(designed.rank + recorded.rank, 3);
  EXPECT_GE(std::min(designed.rank, recorded.rank), 1);
}

// 199.7 Hz (samples between the compare instants, which the C² interpolant
// of the recorded q, qd, qdd fills) is accepted, and its cond is the
// motion's to 1e-6; without qd and qdd the filter estimates them and the
// motion is ranked like any other.
TEST_F(CompareCommandTest, OddRateLogsAreAccepted) {
  const Eigen::Index n = static_cast<Eigen::Index>(std::floor(10.0 * 199.7)) + 1;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / 199.7);
  options_.trajectories = {"general"};
  options_.logs = {WriteLog("odd.csv", t, {"t", "q", "qd", "qdd", "tau"}), WriteLog("q_only.csv", t, {"t", "q", "tau"})};
  options_.trials = 2;
  const CompareReport report = RunCompare(model_, options_);
  ASSERT_EQ(report.motions.size(), 3u);
  // The log ends at its last sample before 10 s: the truth is the motion
  // itself on the log's instants (every duration/samples from 0).
  const MotionComparison& odd = report.motions[1];
  EXPECT_NEAR(odd.duration, static_cast<double>(n - 1) / 199.7, 1e-12);
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 10.0, .paper_qdd = 0.5});
  const DesignRegressor regressor = DesignRegressor::JointTorque(model_, *ParseFrictionTerms(options_.friction, nullptr));
  std::vector<double> times;
  for (int k = 0; k < options_.samples; ++k) times.push_back(k * odd.duration / options_.samples);
  const Identifiability truth = ComputeIdentifiability(regressor.Stack(*motion, times));
  EXPECT_NEAR(odd.designed.cond / truth.cond, 1.0, 1e-6);  // measured 2e-11
  EXPECT_NEAR(odd.designed.log_det, truth.log_det, 1e-6);
  EXPECT_TRUE(odd.unexcited.empty());
  EXPECT_TRUE(std::isfinite(odd.designed.cond));
  const MotionComparison& filtered = report.motions[2];
  EXPECT_TRUE(filtered.unexcited.empty());
  EXPECT_TRUE(std::isfinite(filtered.designed.cond));
  EXPECT_LT(filtered.duration, 10.0 - 2 * 0.5 + 1e-9);  // 5/cutoff = 0.5 s of filter transients dropped at each end
  std::vector<int> ranks;
  for (const MotionComparison& m : report.motions) ranks.push_back(m.rank);
  std::sort(ranks.begin(), ranks.end());
  EXPECT_EQ(ranks, (std::vector<int>{1, 2, 3}));
}

}  // namespace
}  // namespace idbench
