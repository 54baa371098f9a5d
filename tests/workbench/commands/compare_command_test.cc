// compare on recorded logs: a noise-free log written from a built-in motion
// (inverse dynamics, ident/synthetic_log.h) has the identifiability of the
// motion it came from, whatever its rate; a log without qd/qdd goes through
// identify's zero-phase filter; a recorded log is ranked with the designed
// motions and not simulated.
#include "idbench/workbench/commands/compare_command.h"
#include "idbench/workbench/commands/montecarlo_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include <Eigen/Cholesky>

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
// 4156.94182086 both). Bullet replays the log as it runs the motion, but the
// simulation's Runge–Kutta stages also ask for the reference between steps,
// where the log is interpolated linearly (up to dt²/8·|qdd| ≈ 5e-7 rad off the
// motion): realised cond 4156.9418246 for the motion and 4156.9892871 for the
// log (1.1e-5), Monte-Carlo error 0.0491116 and 0.0491072 (9.0e-5), %σ within
// 5.0e-5. (With one Euler step per step the controller never looked between
// steps, and the two agreed to 1e-6.)
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
  // Bullet replays the log (linear between its samples) as it runs the
  // motion: the same realised states to the interpolation's error, the same
  // seeded noise, the same Monte-Carlo error and %σ to 2e-4.
  EXPECT_TRUE(recorded.simulated);
  EXPECT_NEAR(recorded.realised.cond / designed.realised.cond, 1.0, 2e-4);
  EXPECT_NEAR(recorded.mean_relative_error / designed.mean_relative_error, 1.0, 2e-4);
  ASSERT_EQ(recorded.predicted_sigma.size(), designed.predicted_sigma.size());
  for (Eigen::Index k = 0; k < recorded.predicted_sigma.size(); ++k) {
    EXPECT_NEAR(recorded.predicted_sigma[k] / designed.predicted_sigma[k], 1.0, 2e-4) << report.parameter_names[k];
  }
  // The simulation tracks the motion itself to the integrator's error.
  EXPECT_NEAR(designed.realised.cond / designed.designed.cond, 1.0, 1e-6);
  // Equal cond: both ranked, 1 and 2.
  EXPECT_EQ(designed.rank + recorded.rank, 3);
  EXPECT_GE(std::min(designed.rank, recorded.rank), 1);
}

// 199.7 Hz (samples between the compare instants, which linear
// interpolation of the recorded q, qd, qdd fills) is accepted, and its cond
// is the motion's to 1e-3; without qd and qdd the filter estimates them and the
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
  EXPECT_NEAR(odd.designed.cond / truth.cond, 1.0, 1e-3);  // measured 1.5e-4 (4157.569 vs 4156.942)
  EXPECT_NEAR(odd.designed.log_det, truth.log_det, 1e-2 * std::abs(truth.log_det));
  // Simulated over 10 s (40 steps of 1 ms between instants): the motion's
  // Monte-Carlo error within 1 % (measured 0.04976 vs 0.04966).
  EXPECT_TRUE(odd.simulated);
  EXPECT_NEAR(odd.mean_relative_error / report.motions[0].mean_relative_error, 1.0, 1e-2);
  EXPECT_TRUE(odd.unexcited.empty());
  EXPECT_TRUE(std::isfinite(odd.designed.cond));
  const MotionComparison& filtered = report.motions[2];
  EXPECT_TRUE(filtered.unexcited.empty());
  EXPECT_TRUE(std::isfinite(filtered.designed.cond));
  // 5/cutoff = 0.5 s of filter transients dropped at each end, then cut to
  // whole samples·dt = 0.25 s for the simulation: 8.75 s.
  EXPECT_NEAR(filtered.duration, 8.75, 1e-9);
  std::vector<int> ranks;
  for (const MotionComparison& m : report.motions) ranks.push_back(m.rank);
  std::sort(ranks.begin(), ranks.end());
  EXPECT_EQ(ranks, (std::vector<int>{1, 2, 3}));
}

// A log shorter than samples·dt (1.9 s < 1900 × 10 ms) cannot be simulated
// on whole steps: not simulated (NaN realised cond and Monte-Carlo error),
// its σ that of weighted least squares with the known torque noise on the
// recorded states (the instants on its samples), here against the normal
// equations of the motion itself.
TEST_F(CompareCommandTest, ShortLogIsNotSimulated) {
  options_.samples = 1900;
  options_.dt = 1e-2;
  options_.logs = {WriteLog("short.csv", Eigen::VectorXd::LinSpaced(1901, 0.0, 1.9), {"t", "q", "qd", "qdd", "tau"})};
  const CompareReport report = RunCompare(model_, options_);
  ASSERT_EQ(report.motions.size(), 1u);
  const MotionComparison& m = report.motions[0];
  ASSERT_TRUE(m.unexcited.empty());
  EXPECT_FALSE(m.simulated);
  EXPECT_TRUE(std::isnan(m.realised.cond));
  EXPECT_TRUE(std::isnan(m.mean_relative_error));
  EXPECT_EQ(m.rank, 1);
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 10.0, .paper_qdd = 0.5});
  const DesignRegressor regressor = DesignRegressor::JointTorque(model_, *ParseFrictionTerms(options_.friction, nullptr));
  std::vector<double> times;
  for (int k = 0; k < options_.samples; ++k) times.push_back(k * 1.9 / options_.samples);
  Eigen::MatrixXd W = regressor.Stack(*motion, times);
  for (Eigen::Index r = 0; r < W.rows(); ++r) W.row(r) /= report.tau_noise[static_cast<size_t>(r % 6)];
  const Eigen::MatrixXd covariance = (W.transpose() * W).ldlt().solve(Eigen::MatrixXd::Identity(W.cols(), W.cols()));
  ASSERT_EQ(report.tau_noise, DefaultTorqueNoise(6));  // none given: the default, as run
  ASSERT_EQ(m.predicted_sigma.size(), W.cols());
  for (Eigen::Index k = 0; k < W.cols(); ++k) {
    EXPECT_NEAR(m.predicted_sigma[k] / std::sqrt(covariance(k, k)), 1.0, 1e-6) << report.parameter_names[k];
  }
}

// The brief report: the settings, the best-ranked motion with the numbers of
// its row, the motions that fail a check and the status. The paper motion
// (hinges 1 and 2 accelerating from rest: q = 0.5 qdd t², 25 rad at 10 s)
// leaves most of the puma560's parameters unexcited and leaves its joint
// limits; over 2 s (1 rad), with no clearance check, it is only unexcited.
TEST_F(CompareCommandTest, BriefReportNamesTheBestMotionAndTheFailures) {
  options_.trajectories = {"general", "paper"};
  CompareReport report = RunCompare(model_, options_);
  ASSERT_EQ(report.motions.size(), 2u);
  const MotionComparison& general = report.motions[0];
  const MotionComparison& paper = report.motions[1];
  ASSERT_TRUE(general.limits.feasible()) << general.limits.Explain();
  ASSERT_TRUE(general.unexcited.empty());
  EXPECT_FALSE(paper.limits.feasible());
  EXPECT_FALSE(paper.unexcited.empty());
  EXPECT_EQ(general.rank, 1);
  EXPECT_EQ(report.status, CompareStatus::kOutsideLimits);
  const std::string table = FormatCompareTable(options_, report);
  const std::string headline = table.substr(0, table.find('\n'));
  EXPECT_EQ(headline, "compare: torque model, " + std::to_string(report.parameter_names.size()) +
                          " parameters, 250 samples per motion, 2 noisy trials");
  std::string brief = report.BriefReport();
  ASSERT_EQ(brief.rfind(headline + "\nbest: general (cond(W) ", 0), 0u) << brief;
  double cond = 0.0, error = 0.0;
  ASSERT_EQ(std::sscanf(brief.c_str() + headline.size(), "\nbest: general (cond(W) %lg, MC error %lg)", &cond, &error), 2)
      << brief;
  EXPECT_NEAR(cond, general.designed.cond, 1e-4 * general.designed.cond);
  EXPECT_NEAR(error, general.mean_relative_error, 1e-3 * general.mean_relative_error);
  const std::string failed = "outside the limits: paper\nnot exciting every parameter: paper\noutside limits\n";
  ASSERT_GE(brief.size(), failed.size());
  EXPECT_EQ(brief.substr(brief.size() - failed.size()), failed) << brief;

  // The general motion alone: compared.
  options_.trajectories = {"general"};
  report = RunCompare(model_, options_);
  EXPECT_EQ(report.status, CompareStatus::kCompared);
  brief = report.BriefReport();
  // Three lines: the settings, the best motion, the status.
  EXPECT_EQ(std::count(brief.begin(), brief.end(), '\n'), 3) << brief;
  EXPECT_NE(brief.find("\nbest: general (cond(W) "), std::string::npos) << brief;
  EXPECT_EQ(brief.substr(brief.size() - 11), ")\ncompared\n") << brief;

  // The paper motion over 2 s within the joint limits: not excited, no best.
  options_.trajectories = {"paper"};
  options_.duration = 2.0;
  options_.clearance = -1.0;
  report = RunCompare(model_, options_);
  ASSERT_EQ(report.motions.size(), 1u);
  EXPECT_TRUE(report.motions[0].limits.feasible()) << report.motions[0].limits.Explain();
  EXPECT_EQ(report.status, CompareStatus::kNotExcited);
  brief = report.BriefReport();
  EXPECT_EQ(brief.find("best:"), std::string::npos) << brief;
  const std::string unexcited = "\nnot exciting every parameter: paper\nnot excited\n";
  EXPECT_EQ(brief.substr(brief.find('\n')), unexcited) << brief;
}

}  // namespace
}  // namespace idbench
