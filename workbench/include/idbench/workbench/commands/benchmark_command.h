// `idbench benchmark`: a Monte-Carlo benchmark that ranks the joint-torque
// estimators on closed-loop data, as BIRDy (TUM-ICS/BIRDy) does. Every trial
// simulates the robot under its controller along the reference with a noise
// preset's sensors (simulate_command.h SimulateClosedLoopLog), reads the log
// as a robot records it (t, q, τ: qd, qdd from identify's filter, the torques
// read as held commands, JointLogFormat::torque_held) and identifies it with
// each estimator exactly as `identify` does (IdentifyPreparedLogs, its
// closed-loop estimators re-simulating the loop with the same controller and
// reference). The truth is the robot file's own base parameters: C·π of its
// standard parameters with the friction terms identified (the joints' friction
// and rotor inertia the simulation's plant acts with).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/sensor_model.h"
#include "idbench/ident/joint_torque_identifier.h"

namespace idbench {

struct BenchmarkOptions {
  std::string robot = "puma560";        // built-in name or URDF path
  std::string trajectory = "general";   // reference: built-in motion or .json/.csv file (trajectory_file.h)
  double duration = 10.0;               // [s] of a built-in motion; a file brings its own
  std::string controller;               // controller file (controller_file.h), required
  std::vector<TorqueEstimator> estimators{TorqueEstimator::kOls, TorqueEstimator::kWls, TorqueEstimator::kTls,
                                          TorqueEstimator::kIrls, TorqueEstimator::kInstrumentalVariables,
                                          TorqueEstimator::kDidim};
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};  // identified terms (identify's)
  int trials = 10;                      // per preset, in [1, kMaxTrials]
  std::vector<NoisePreset> presets{NoisePreset::kLow};  // each distinct, at most kNoisePresetNames' count
  unsigned seed = 1;
  int threads = 1;                      // trials run at once, in [0, kMaxThreads]; 0: the hardware's
  // The shard_index-th (from 0) of shard_count disjoint slices of the trials:
  // trial j of the run (presets in order, then trials) belongs to shard
  // j mod shard_count. 1 shard: the whole run.
  int shard_index = 0;
  int shard_count = 1;
  std::string out_dir = "out/benchmark";

  static constexpr int kMaxTrials = 100000;
  static constexpr int kMaxThreads = 256;
  static constexpr int kMaxShards = 100000;
  static constexpr int kMaxEstimators = 7;  // each of TorqueEstimator at most once

  // Checks the options alone; *why names the field ("trials: ...").
  bool IsValid(std::string* why) const;
};

// The seed of a trial's sensors: SplitMix64 of (seed, preset, trial) only,
// so that a shard, a run of fewer presets or another thread count draws the
// same noise for the same trial.
unsigned BenchmarkTrialSeed(unsigned seed, NoisePreset preset, int trial);

// One estimator on one trial. Errors, with β the truth and β̂ the estimate:
//   parameter_error = ‖β̂ − β‖₂ / (½ (‖β̂‖₂ + ‖β‖₂))   (symmetric relative error)
//   torque_error    = ‖τ̂ − τ‖₂ / ‖τ‖₂ on the trial's own log, its equations as
//                     the fit used them (filtered in parallel; identify's "fit")
//   position_error  = ‖Q − Q̂‖_F / ‖Q‖_F, Q the trial's measured positions, Q̂
//                     the closed loop re-simulated with β̂ (the controller, the
//                     reference; ClosedLoopPositionError); NaN when that fails
//   coverage_95     = fraction of the base parameters with |β̂_i − β_i| ≤ 1.96 σ_i,
//                     σ the estimator's own (NaN for pc, which has none)
// diverged: parameter_error > kDivergenceFactor × OLS's on the same trial
// (BIRDy's rule, OLS being every estimator's starting point), not finite, or
// the estimator failed (message says why).
struct BenchmarkEstimate {
  TorqueEstimator estimator = TorqueEstimator::kOls;
  double parameter_error = 0.0;
  double torque_error = 0.0;
  double position_error = 0.0;
  double coverage_95 = 0.0;
  double seconds = 0.0;  // wall time of the identification [s] (not the position error's re-simulation)
  Eigen::VectorXd beta;   // the estimate (n_base; empty when it failed)
  Eigen::VectorXd sigma;  // its printed σ (n_base; NaN for pc)
  bool diverged = false;
  std::string message;   // a closed-loop estimator that did not converge, or the failure
};
inline constexpr double kDivergenceFactor = 50.0;

struct BenchmarkTrial {
  NoisePreset preset = NoisePreset::kLow;
  int trial = 0;          // from 0, per preset
  unsigned seed = 0;      // BenchmarkTrialSeed
  std::vector<BenchmarkEstimate> estimates;  // in BenchmarkOptions::estimators' order
};

// Mean, sample standard deviation (n − 1; 0 for one value) and median over
// the trials that did not diverge (seconds: over all trials). NaN when there
// is none. The closed-loop estimators' errors have heavy tails (a few
// re-simulations that run away), which the median shows beside the mean.
struct BenchmarkStatistic {
  double mean = 0.0;
  double std = 0.0;
  double median = 0.0;
};
struct BenchmarkSummary {
  TorqueEstimator estimator = TorqueEstimator::kOls;
  NoisePreset preset = NoisePreset::kLow;
  int trials = 0;
  BenchmarkStatistic parameter_error, torque_error, seconds;
  // Over the trials kept whose re-simulation ran (position_trials of them:
  // an estimate whose mass matrix is not positive definite along the motion
  // cannot be simulated, e.g. OLS on a weakly excited arm).
  BenchmarkStatistic position_error;
  int position_trials = 0;
  double coverage_95 = 0.0;  // mean of the trials' coverage_95 (NaN for pc)
  // Is σ a claim the trials bear out: the median over the base parameters of
  // RMS_trials(σ_i) / std_trials(β̂_i), over the trials that did not diverge
  // (1: the printed σ is the spread; NaN with fewer than 2 trials, or for pc).
  double sigma_ratio = 0.0;
  int diverged = 0;
};

struct BenchmarkResult {
  // What the run was (written to benchmark.json; a merge checks that every
  // shard's is the same).
  std::string robot, trajectory, controller;
  std::vector<std::string> friction;
  std::vector<TorqueEstimator> estimators;
  std::vector<NoisePreset> presets;
  int trials = 0;  // per preset, of the whole run
  unsigned seed = 0;
  int shard_index = 0, shard_count = 1;
  std::vector<std::string> base_parameter_names;
  Eigen::VectorXd beta_true;  // the robot file's base parameters (n_base)
  // The trials run, in run order (presets, then trials); a shard's own only.
  std::vector<BenchmarkTrial> trials_run;
  // Per preset × estimator, in that order (SummarizeBenchmark).
  std::vector<BenchmarkSummary> summary;
};

// Called after each trial (from the thread that ran it, one call at a time):
// trials done and to do in this run (this shard).
using BenchmarkProgress = std::function<void(int done, int total)>;

// Runs this shard's trials on options.threads threads; the result does not
// depend on the thread count. Throws std::invalid_argument when the options,
// the controller or trajectory file do not fit the robot (before any trial),
// std::runtime_error when a simulation fails. An estimator failing on a trial
// is recorded there (diverged), not thrown.
BenchmarkResult RunBenchmark(const RobotModel& model, const BenchmarkOptions& options,
                             const BenchmarkProgress& progress = {});

// Fills result->summary from result->trials_run.
void SummarizeBenchmark(BenchmarkResult* result);

// The table: one row per preset × estimator.
std::string FormatBenchmarkTable(const BenchmarkResult& result);

// benchmark.json: the run, "results" (the summary: per estimator and preset
// "estimator", "preset", "trials", "parameter_error": {"mean", "std", "median"},
// "torque_error": {...}, "position_error": {...}, "coverage_95", "sigma_ratio", "diverged", "seconds": {...}) and
// "trials" (every trial's raw values), doubles written so that they read back
// bit for bit (NaN as null). A shard's adds "shard": "K/N".
std::string FormatBenchmarkJson(const BenchmarkResult& result);

// Reads benchmark.json back; `source` names it in messages. Throws
// std::invalid_argument "source: field: what".
BenchmarkResult ParseBenchmarkJson(const std::string& text, const std::string& source);

// Joins shards (ParseBenchmarkJson) into the result the whole run gives, its
// summary recomputed, bit for bit the same. Throws std::invalid_argument
// naming the source when the runs differ, a trial is missing or given twice.
// sources name the parts in messages (same size as parts).
BenchmarkResult MergeBenchmarkResults(const std::vector<BenchmarkResult>& parts,
                                      const std::vector<std::string>& sources);

}  // namespace idbench
