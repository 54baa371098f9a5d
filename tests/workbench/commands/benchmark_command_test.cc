// RunBenchmark (issue 37, item 3) on the 3-joint table_arm under a PID: the
// result does not depend on the threads; shards merged are the single run;
// noise-free every estimator recovers the robot file's base parameters to the
// filter's floor (DIDIM aside); under BIRDy's high noise, the numbers measured.
#include "idbench/workbench/commands/benchmark_command.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/robot_library.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class BenchmarkCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("idbench_benchmark_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    options_.robot = kRobot;
    options_.controller = (dir_ / "pid.json").string();
    // The gains of identify_cli_test.cc's closed-loop tests.
    std::ofstream(options_.controller) << R"({"kp": [400, 400, 200], "kd": [10, 10, 5], "feedforward": "model"})";
    options_.friction = {"none"};  // table_arm's joints have none
    options_.out_dir = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The built-in general motion cut to `duration` [s], as a trajectory file.
  void ShortTrajectory(double duration) {
    options_.trajectory = (dir_ / "short.json").string();
    std::ofstream(options_.trajectory) << FormatTrajectoryJson(*MakeGeneralMotion(model_.n_dof(), duration));
  }

  // The JSON with every wall time set to 0: what a run determines.
  static std::string WithoutTimes(BenchmarkResult result) {
    for (BenchmarkTrial& trial : result.trials_run) {
      for (BenchmarkEstimate& estimate : trial.estimates) estimate.seconds = 0.0;
    }
    SummarizeBenchmark(&result);
    return FormatBenchmarkJson(result);
  }

  const BenchmarkSummary& Summary(const BenchmarkResult& result, TorqueEstimator estimator) {
    for (const BenchmarkSummary& s : result.summary) {
      if (s.estimator == estimator) return s;
    }
    throw std::logic_error("no summary");
  }

  static constexpr const char* kRobot = IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf";
  fs::path dir_;
  BenchmarkOptions options_;
  RobotModel model_ = LoadRobot(kRobot).model;
};

// The same seed gives the same trials on 1 and 2 threads, bit for bit; each
// trial's seed depends on (seed, preset, trial) only.
TEST_F(BenchmarkCommandTest, TheResultDoesNotDependOnTheThreads) {
  ShortTrajectory(2.0);
  options_.estimators = {TorqueEstimator::kOls, TorqueEstimator::kDidim};
  options_.presets = {NoisePreset::kHigh};
  options_.trials = 3;
  options_.threads = 1;
  const BenchmarkResult one = RunBenchmark(model_, options_);
  options_.threads = 2;
  const BenchmarkResult two = RunBenchmark(model_, options_);
  EXPECT_EQ(WithoutTimes(one), WithoutTimes(two));
  ASSERT_EQ(one.trials_run.size(), 3u);
  EXPECT_EQ(one.trials_run[2].seed, BenchmarkTrialSeed(options_.seed, NoisePreset::kHigh, 2));
  EXPECT_NE(one.trials_run[1].seed, one.trials_run[2].seed);
  // Different trials draw different noise: different errors.
  EXPECT_NE(one.trials_run[0].estimates[0].parameter_error, one.trials_run[1].estimates[0].parameter_error);
}

// Four shards, written and read back, merge into the single run's
// benchmark.json; the single run read back and merged alone gives its own
// bytes, wall times included (the doubles round-trip).
TEST_F(BenchmarkCommandTest, FourShardsMergedAreTheSingleRun) {
  ShortTrajectory(2.0);
  options_.estimators = {TorqueEstimator::kOls, TorqueEstimator::kWls};
  options_.presets = {NoisePreset::kLow, NoisePreset::kHigh};
  options_.trials = 2;
  const BenchmarkResult single = RunBenchmark(model_, options_);
  const std::string single_json = FormatBenchmarkJson(single);
  EXPECT_EQ(FormatBenchmarkJson(MergeBenchmarkResults({ParseBenchmarkJson(single_json, "single")}, {"single"})),
            single_json);
  std::vector<BenchmarkResult> parts;
  std::vector<std::string> sources;
  for (int k = 0; k < 4; ++k) {
    options_.shard_index = k;
    options_.shard_count = 4;
    const BenchmarkResult shard = RunBenchmark(model_, options_);
    ASSERT_EQ(shard.trials_run.size(), 1u);  // 2 presets × 2 trials over 4 shards
    sources.push_back("shard" + std::to_string(k));
    parts.push_back(ParseBenchmarkJson(FormatBenchmarkJson(shard), sources.back()));
  }
  // Given in any order.
  std::swap(parts[0], parts[3]);
  std::swap(sources[0], sources[3]);
  const BenchmarkResult merged = MergeBenchmarkResults(parts, sources);
  EXPECT_EQ(WithoutTimes(merged), WithoutTimes(single));
  // A shard missing, or given twice, is named.
  try {
    MergeBenchmarkResults({parts[0], parts[1], parts[2]}, {sources[0], sources[1], sources[2]});
    ADD_FAILURE() << "a missing shard was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("is in none of the results given (a shard is missing)"), std::string::npos)
        << e.what();
  }
  try {
    MergeBenchmarkResults({parts[0], parts[1], parts[2], parts[3], parts[1]},
                          {sources[0], sources[1], sources[2], sources[3], "again"});
    ADD_FAILURE() << "a shard given twice was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("again: trial"), std::string::npos) << e.what();
  }
  BenchmarkResult other = parts[1];
  other.seed += 1;
  try {
    MergeBenchmarkResults({parts[0], other}, {"a", "b"});
    ADD_FAILURE() << "shards of different seeds were merged";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("b: seed: not the same as in a"), std::string::npos) << e.what();
  }
}

// Noise-free, read as t, q, τ with held torques: every estimator recovers the
// robot file's base parameters to the filter's floor (≤ 1e-4; identify
// measured 4e-6 on this arm, docs/commands/simulate.md), DIDIM below it. DIDIM
// reads its re-simulation's q̈ at a sample across the two holds, as the held
// torque is read (ClosedLoopEstimatorOptions::torque_held); pairing the held
// torques with the one-sided q̈ of the command just given, it stayed at 0.0094
// on this 4 s motion.
TEST_F(BenchmarkCommandTest, NoiseFreeEveryEstimatorReachesTheFiltersFloor) {
  ShortTrajectory(4.0);
  options_.estimators = {TorqueEstimator::kOls,  TorqueEstimator::kWls, TorqueEstimator::kPhysicallyConsistent,
                         TorqueEstimator::kTls,  TorqueEstimator::kIrls, TorqueEstimator::kInstrumentalVariables,
                         TorqueEstimator::kDidim};
  options_.presets = {NoisePreset::kNone};
  options_.trials = 1;
  const BenchmarkResult result = RunBenchmark(model_, options_);
  ASSERT_EQ(result.summary.size(), 7u);
  for (const BenchmarkSummary& s : result.summary) {
    std::printf("noise-free %s: parameter error %.3g, torque error %.3g, position error %.3g\n",
                std::string(ToString(s.estimator)).c_str(), s.parameter_error.mean, s.torque_error.mean,
                s.position_error.mean);
    if (s.estimator == TorqueEstimator::kDidim) {
      // Its regressor is the re-simulation's exact states, q̈ read across the
      // holds as the log's τ is: below the filter's floor (measured 7.5e-10).
      EXPECT_LE(s.parameter_error.mean, 1e-8);
      EXPECT_EQ(s.diverged, 0);
      EXPECT_LT(s.position_error.mean, 1e-10);
    } else {
      EXPECT_LE(s.parameter_error.mean, 1e-4) << ToString(s.estimator);
      EXPECT_EQ(s.diverged, 0) << ToString(s.estimator);
      // Re-simulated with the estimate, the loop retraces the log (Bullet's
      // plant against the regressor's forward dynamics; measured 2.2e-8 to
      // 2.7e-8, the parameters' error being ~5e-6).
      EXPECT_EQ(s.position_trials, 1);
      EXPECT_LT(s.position_error.mean, 1e-6) << ToString(s.estimator);
    }
  }
}

// With BIRDy's high noise (1e-2° on the q the PID feeds back, 0.1 N m on τ)
// the closed-loop estimators do NOT beat OLS on this arm: over 24 trials of
// 10 s (seed 7; docs/commands/benchmark.md's table-arm-24) the mean errors
// are OLS 0.0298, IV 0.195, DIDIM 0.0596 (medians 0.026, 0.026, 0.027), IV
// and DIDIM near OLS on most trials and running away on a few. On 6 trials
// of 4 s (measured: OLS mean 0.0294; medians OLS 0.028, IV 1.01, DIDIM 0.29)
// both are worse than OLS: asserted, so that a change making them better
// shows here.
TEST_F(BenchmarkCommandTest, ClosedLoopEstimatorsUnderHighNoiseAsMeasured) {
  ShortTrajectory(4.0);
  options_.estimators = {TorqueEstimator::kOls, TorqueEstimator::kInstrumentalVariables, TorqueEstimator::kDidim};
  options_.presets = {NoisePreset::kHigh};
  options_.trials = 6;
  options_.threads = 2;
  const BenchmarkResult result = RunBenchmark(model_, options_);
  std::fputs(FormatBenchmarkTable(result).c_str(), stdout);
  const BenchmarkSummary& ols = Summary(result, TorqueEstimator::kOls);
  const BenchmarkSummary& iv = Summary(result, TorqueEstimator::kInstrumentalVariables);
  const BenchmarkSummary& didim = Summary(result, TorqueEstimator::kDidim);
  for (const BenchmarkSummary* s : {&ols, &iv, &didim}) EXPECT_EQ(s->trials, 6);
  EXPECT_EQ(ols.diverged, 0);
  EXPECT_NEAR(ols.parameter_error.mean, 0.0294, 0.02 * 0.0294);
  EXPECT_NEAR(ols.sigma_ratio, 0.834, 0.02 * 0.834);  // σ within 17 % of the spread of 6 trials (measured)
  // OLS's estimate is no mechanism along the motion on 2 of the 6 trials
  // (its mass matrix not positive definite: this 4 s motion barely excites
  // some directions), so its position error is over 4 (measured).
  EXPECT_EQ(ols.position_trials, 4);
  EXPECT_GT(iv.parameter_error.median, ols.parameter_error.median);
  EXPECT_GT(didim.parameter_error.median, ols.parameter_error.median);
}

// σ against the spread, by hand: parameter 0 has estimates 1, 2, 3 (std 1)
// with σ 2 (ratio 2), parameter 1 has 0, 0, 3 (std √3) with σ √3 (ratio 1):
// the median is 1.5. A diverged trial is left out; pc has no σ.
TEST(BenchmarkSummaryTest, SigmaRatioIsTheMedianOfRmsSigmaOverTheSpread) {
  BenchmarkResult result;
  result.estimators = {TorqueEstimator::kOls};
  result.presets = {NoisePreset::kLow};
  result.trials = 4;
  result.beta_true = Eigen::Vector2d(2.0, 1.0);
  const double b0[] = {1.0, 2.0, 3.0, 100.0}, b1[] = {0.0, 0.0, 3.0, 100.0};
  for (int t = 0; t < 4; ++t) {
    BenchmarkTrial trial;
    trial.trial = t;
    BenchmarkEstimate e;
    e.beta = Eigen::Vector2d(b0[t], b1[t]);
    e.sigma = Eigen::Vector2d(2.0, std::sqrt(3.0));
    e.diverged = t == 3;
    trial.estimates = {e};
    result.trials_run.push_back(trial);
  }
  SummarizeBenchmark(&result);
  ASSERT_EQ(result.summary.size(), 1u);
  EXPECT_NEAR(result.summary[0].sigma_ratio, 1.5, 1e-12);
  EXPECT_EQ(result.summary[0].diverged, 1);
  // Read back from benchmark.json: the same.
  const BenchmarkResult back = ParseBenchmarkJson(FormatBenchmarkJson(result), "json");
  EXPECT_EQ(FormatBenchmarkJson(back), FormatBenchmarkJson(result));
  for (BenchmarkTrial& trial : result.trials_run) trial.estimates[0].sigma.setConstant(std::nan(""));
  SummarizeBenchmark(&result);
  EXPECT_TRUE(std::isnan(result.summary[0].sigma_ratio));
}

// Options are checked before any work, each message naming its field.
TEST_F(BenchmarkCommandTest, BadOptionsAreNamed) {
  auto why = [&](BenchmarkOptions options) {
    std::string message;
    EXPECT_FALSE(options.IsValid(&message));
    return message;
  };
  BenchmarkOptions o = options_;
  o.trials = 0;
  EXPECT_EQ(why(o), "trials: must be in [1, 100000], got 0");
  o = options_;
  o.controller.clear();
  EXPECT_EQ(why(o).rfind("controller: ", 0), 0u);
  o = options_;
  o.estimators = {TorqueEstimator::kOls, TorqueEstimator::kOls};
  EXPECT_EQ(why(o), "estimators: 'ols' is given twice");
  o = options_;
  o.presets = {NoisePreset::kHigh, NoisePreset::kHigh};
  EXPECT_EQ(why(o), "presets: 'high' is given twice");
  o = options_;
  o.shard_index = 4;
  o.shard_count = 4;
  EXPECT_EQ(why(o), "shard: expected K/N with 0 <= K < N <= 100000, got 4/4");
  o = options_;
  o.threads = -1;
  EXPECT_EQ(why(o).rfind("threads: ", 0), 0u);
  // The controller file is read before any trial: its key named.
  std::ofstream(options_.controller) << R"({"kp": [1, 2], "kd": 1})";
  try {
    RunBenchmark(model_, options_);
    ADD_FAILURE() << "a controller for 2 joints was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kp: expected one value or 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace idbench
