#include "idbench/workbench/commands/benchmark_command.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "idbench/ident/closed_loop_estimators.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/controller_file.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "number_format.h"

namespace idbench {

bool BenchmarkOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (robot.empty()) return fail("robot: a built-in name or URDF file is required");
  if (trajectory.empty()) return fail("trajectory: a built-in motion or trajectory file is required");
  if (controller.empty()) {
    return fail("controller: the benchmark simulates the robot under its controller: a controller file is required");
  }
  if (estimators.empty() || static_cast<int>(estimators.size()) > kMaxEstimators) {
    return fail("estimators: expected 1 to " + std::to_string(kMaxEstimators) + " estimators, got " +
                std::to_string(estimators.size()));
  }
  for (size_t i = 0; i < estimators.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (estimators[k] == estimators[i]) {
        return fail("estimators: '" + std::string(ToString(estimators[i])) + "' is given twice");
      }
    }
  }
  if (presets.empty() || presets.size() > kNoisePresetNames.names.size()) {
    return fail("presets: expected 1 to " + std::to_string(kNoisePresetNames.names.size()) + " noise presets, got " +
                std::to_string(presets.size()));
  }
  for (size_t i = 0; i < presets.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (presets[k] == presets[i]) {
        return fail("presets: '" + std::string(kNoisePresetNames.Name(presets[i])) + "' is given twice");
      }
    }
  }
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  if (trials < 1 || trials > kMaxTrials) {
    return fail("trials: must be in [1, " + std::to_string(kMaxTrials) + "], got " + std::to_string(trials));
  }
  if (threads < 0 || threads > kMaxThreads) {
    return fail("threads: must be in [0, " + std::to_string(kMaxThreads) + "] (0: the hardware's), got " +
                std::to_string(threads));
  }
  if (shard_count < 1 || shard_count > kMaxShards || shard_index < 0 || shard_index >= shard_count) {
    return fail("shard: expected K/N with 0 <= K < N <= " + std::to_string(kMaxShards) + ", got " +
                std::to_string(shard_index) + "/" + std::to_string(shard_count));
  }
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

unsigned BenchmarkTrialSeed(unsigned seed, NoisePreset preset, int trial) {
  // SplitMix64 (Steele, Lea & Flood 2014) over the three, one after the other.
  auto mix = [](uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const uint64_t h = mix(mix(mix(seed) ^ static_cast<uint64_t>(preset)) ^ static_cast<uint64_t>(trial));
  return static_cast<unsigned>(h >> 32);
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The half-width of a normal 95 % interval in σ.
constexpr double kBenchmarkInterval95 = 1.96;

// The symmetric relative error ‖β̂ − β‖ / (½ (‖β̂‖ + ‖β‖)).
double SymmetricRelativeError(const Eigen::VectorXd& estimate, const Eigen::VectorXd& truth) {
  return (estimate - truth).norm() / (0.5 * (estimate.norm() + truth.norm()));
}

// What every trial shares: the model, the truth, the identify options, and
// what re-simulating an estimate takes (the reference, the controller, the
// base).
struct BenchmarkSetup {
  const RobotModel* model = nullptr;
  const BenchmarkOptions* options = nullptr;
  Eigen::VectorXd beta_true;
  const Trajectory* reference = nullptr;
  JointControllerOptions controller;
  FrictionModel friction;
  const BaseParameters* base = nullptr;
};

// One estimator on a trial's prepared log, as `identify` runs it.
// `measured` is the trial's log as recorded (t, q), for the position error.
BenchmarkEstimate Estimate(const BenchmarkSetup& setup, IdentifyOptions identify, const PreparedLog& prepared,
                           const JointLog& measured, TorqueEstimator estimator) {
  BenchmarkEstimate out;
  out.estimator = estimator;
  identify.estimator = estimator;
  if (!IsClosedLoopEstimator(estimator)) {
    identify.controller.clear();
    identify.reference.clear();
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    const IdentifyReport report = IdentifyPreparedLogs(*setup.model, identify, prepared, std::nullopt);
    const JointTorqueIdentification& id = report.identification;
    out.beta = id.beta;
    out.sigma = estimator == TorqueEstimator::kPhysicallyConsistent
                    ? Eigen::VectorXd::Constant(id.beta.size(), kNaN)
                    : Eigen::VectorXd(id.linear.sigma);
    out.parameter_error = SymmetricRelativeError(id.beta, setup.beta_true);
    out.torque_error = id.fit.relative_error;
    if (estimator == TorqueEstimator::kPhysicallyConsistent) {
      out.coverage_95 = kNaN;  // no σ of its own
    } else {
      const Eigen::ArrayXd error = (id.beta - setup.beta_true).cwiseAbs().array();
      out.coverage_95 = static_cast<double>((error <= kBenchmarkInterval95 * id.linear.sigma.array()).count()) /
                        static_cast<double>(error.size());
    }
    if (report.closed_loop && !report.closed_loop->converged) out.message = report.closed_loop->message;
  } catch (const std::exception& e) {
    out.parameter_error = out.torque_error = out.coverage_95 = kNaN;
    out.diverged = true;
    out.message = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The position error: the closed loop re-simulated with the estimate.
  out.position_error = kNaN;
  if (out.beta.size() > 0 && out.beta.allFinite()) {
    try {
      out.position_error = ClosedLoopPositionError(*setup.model, setup.friction, *setup.base, measured,
                                                   *setup.reference, out.beta, setup.controller);
    } catch (const std::runtime_error& e) {
      out.message += std::string(out.message.empty() ? "" : "; ") + "position error: " + e.what();
    }
  }
  return out;
}

// Simulates trial `trial` of `preset` and identifies it with every estimator.
BenchmarkTrial RunTrial(const BenchmarkSetup& setup, NoisePreset preset, int trial) {
  const BenchmarkOptions& options = *setup.options;
  BenchmarkTrial out;
  out.preset = preset;
  out.trial = trial;
  out.seed = BenchmarkTrialSeed(options.seed, preset, trial);
  // 1. The closed loop as `simulate --controller --no-derivatives
  // --noise-preset` runs it; a built-in motion as identify's reference is
  // (10 s; the paper motion at 0.5 rad/s²).
  SimulateOptions simulate;
  simulate.robot = options.robot;
  simulate.trajectory = options.trajectory;
  simulate.duration = BuiltinMotionOptions{}.duration;
  simulate.paper_accel_deg_s2 = BuiltinMotionOptions{}.paper_qdd * 180.0 / std::numbers::pi;
  simulate.controller = options.controller;
  simulate.sensors.record_derivatives = false;
  simulate.sensors.seed = out.seed;
  std::string why;
  if (!ApplyNoisePreset(preset, &simulate.sensors, &why)) throw std::logic_error("benchmark: " + why);
  ClosedLoopLog closed = SimulateClosedLoopLog(*setup.model, simulate);
  JointLog measured;
  measured.t = closed.log.t;
  measured.q = closed.log.q;

  // 2. Read as identify reads such a log: t, q, τ, qd and qdd from the
  // filter, the torques read as held commands (JointLogFormat::torque_held:
  // the filtered qdd at a sample averages the holds on both sides of it).
  // DIDIM too, although its re-simulated states are the plant's own at each
  // sample, where the command just given acts: noise-free it then stays at
  // 0.012 on table_arm (7e-10 with the torques as recorded), but under
  // noise it does better so (median 0.021 against 0.100 over 24 trials of
  // the high preset), and it starts from the OLS of the same log.
  IdentifyOptions identify;
  identify.robot = options.robot;
  identify.data = "trial " + std::to_string(trial) + " (" + std::string(kNoisePresetNames.Name(preset)) + ")";
  identify.friction = options.friction;
  identify.controller = options.controller;
  identify.reference = options.trajectory;
  identify.format.torque_held = true;
  RecordedJointLog recorded;
  recorded.log.t = std::move(closed.log.t);
  recorded.log.q = std::move(closed.log.q);
  recorded.log.tau = std::move(closed.log.tau);
  recorded.lines.resize(static_cast<size_t>(recorded.log.t.size()));
  for (size_t k = 0; k < recorded.lines.size(); ++k) recorded.lines[k] = static_cast<int>(k);
  const PreparedLog prepared = PrepareRecordedJointLog(std::move(recorded), identify.data, identify.preparation(true));

  // 3. Every estimator; OLS (every estimator's start) judges divergence.
  const BenchmarkEstimate ols = Estimate(setup, identify, prepared, measured, TorqueEstimator::kOls);
  for (TorqueEstimator estimator : options.estimators) {
    BenchmarkEstimate estimate =
        estimator == TorqueEstimator::kOls ? ols : Estimate(setup, identify, prepared, measured, estimator);
    if (!std::isfinite(estimate.parameter_error) ||
        (std::isfinite(ols.parameter_error) && estimate.parameter_error > kDivergenceFactor * ols.parameter_error)) {
      estimate.diverged = true;
    }
    out.estimates.push_back(std::move(estimate));
  }
  return out;
}

// Mean and sample standard deviation of `values` (in order); NaN when empty.
BenchmarkStatistic Statistic(const std::vector<double>& values) {
  BenchmarkStatistic s{kNaN, kNaN, kNaN};
  if (values.empty()) return s;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const size_t half = sorted.size() / 2;
  s.median = sorted.size() % 2 ? sorted[half] : 0.5 * (sorted[half - 1] + sorted[half]);
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std = values.size() > 1 ? std::sqrt(squares / static_cast<double>(values.size() - 1)) : 0.0;
  return s;
}

// Median over the base parameters of RMS(σ_i) / std(β̂_i) over the estimates
// (BenchmarkSummary::sigma_ratio); NaN with fewer than 2 or without σ.
double SigmaRatio(const std::vector<const BenchmarkEstimate*>& estimates, Eigen::Index n_base) {
  if (estimates.size() < 2) return kNaN;
  std::vector<double> ratios;
  for (Eigen::Index i = 0; i < n_base; ++i) {
    std::vector<double> values;
    double sigma_squares = 0.0;
    for (const BenchmarkEstimate* e : estimates) {
      if (e->beta.size() != n_base || e->sigma.size() != n_base) return kNaN;
      values.push_back(e->beta[i]);
      sigma_squares += e->sigma[i] * e->sigma[i];
    }
    const double rms_sigma = std::sqrt(sigma_squares / static_cast<double>(estimates.size()));
    ratios.push_back(rms_sigma / Statistic(values).std);
  }
  for (double r : ratios) {
    if (std::isnan(r)) return kNaN;
  }
  return ratios.empty() ? kNaN : Statistic(ratios).median;
}

}  // namespace

BenchmarkResult RunBenchmark(const RobotModel& model, const BenchmarkOptions& options,
                             const BenchmarkProgress& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  // The inputs every trial reads, checked once before any trial runs.
  const JointControllerOptions controller = ReadControllerFile(options.controller, model.n_dof());
  const std::unique_ptr<Trajectory> reference = LoadTrajectoryArg(options.trajectory, model, BuiltinMotionOptions{});
  const FrictionModel friction = ParseFrictionTerms(options.friction, nullptr).value_or(FrictionModel{});

  BenchmarkResult result;
  result.robot = options.robot;
  result.trajectory = options.trajectory;
  result.controller = options.controller;
  result.friction = options.friction;
  result.estimators = options.estimators;
  result.presets = options.presets;
  result.trials = options.trials;
  result.seed = options.seed;
  result.shard_index = options.shard_index;
  result.shard_count = options.shard_count;
  // The truth, on the base identify computes (ComputeBaseParameters' defaults).
  const BaseParameters base = ComputeBaseParameters(model, friction);
  result.base_parameter_names = base.names;
  result.beta_true = base.combination * StandardParameters(model, friction);
  const BenchmarkSetup setup{&model, &options, result.beta_true, reference.get(), controller, friction, &base};

  // This shard's trials, in run order; each runs on whichever thread takes
  // it and lands in its own slot, so the order never depends on the threads.
  std::vector<std::pair<NoisePreset, int>> jobs;
  for (size_t p = 0; p < options.presets.size(); ++p) {
    for (int trial = 0; trial < options.trials; ++trial) {
      const long index = static_cast<long>(p) * options.trials + trial;
      if (index % options.shard_count == options.shard_index) jobs.emplace_back(options.presets[p], trial);
    }
  }
  result.trials_run.resize(jobs.size());
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int n_threads =
      std::max(1, std::min<int>(options.threads == 0 ? hardware : options.threads, static_cast<int>(jobs.size())));
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  int done = 0;
  std::exception_ptr error;
  auto work = [&] {
    for (size_t j = next++; j < jobs.size() && !failed; j = next++) {
      try {
        result.trials_run[j] = RunTrial(setup, jobs[j].first, jobs[j].second);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, static_cast<int>(jobs.size()));
    }
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < n_threads; ++k) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
  SummarizeBenchmark(&result);
  return result;
}

void SummarizeBenchmark(BenchmarkResult* result) {
  result->summary.clear();
  for (NoisePreset preset : result->presets) {
    for (size_t e = 0; e < result->estimators.size(); ++e) {
      BenchmarkSummary s;
      s.estimator = result->estimators[e];
      s.preset = preset;
      std::vector<double> parameter, torque, position, coverage, seconds;
      std::vector<const BenchmarkEstimate*> kept;
      for (const BenchmarkTrial& trial : result->trials_run) {
        if (trial.preset != preset) continue;
        const BenchmarkEstimate& estimate = trial.estimates.at(e);
        ++s.trials;
        seconds.push_back(estimate.seconds);
        if (estimate.diverged) {
          ++s.diverged;
          continue;
        }
        parameter.push_back(estimate.parameter_error);
        torque.push_back(estimate.torque_error);
        if (std::isfinite(estimate.position_error)) position.push_back(estimate.position_error);
        coverage.push_back(estimate.coverage_95);
        kept.push_back(&estimate);
      }
      s.sigma_ratio = SigmaRatio(kept, result->beta_true.size());
      s.parameter_error = Statistic(parameter);
      s.torque_error = Statistic(torque);
      s.position_error = Statistic(position);
      s.position_trials = static_cast<int>(position.size());
      s.seconds = Statistic(seconds);
      s.coverage_95 = Statistic(coverage).mean;
      result->summary.push_back(s);
    }
  }
}

std::string FormatBenchmarkTable(const BenchmarkResult& result) {
  char line[512];
  std::snprintf(line, sizeof line,
                "Benchmark of %s along '%s' under %s: %d trials per noise preset, %d base parameters, seed %u%s\n\n",
                result.robot.c_str(), result.trajectory.c_str(), result.controller.c_str(), result.trials,
                static_cast<int>(result.beta_true.size()), result.seed,
                result.shard_count > 1
                    ? (", shard " + std::to_string(result.shard_index) + "/" + std::to_string(result.shard_count)).c_str()
                    : "");
  std::string out = line;
  std::snprintf(line, sizeof line, "%-6s  %-9s  %32s  %21s  %15s  %9s  %8s  %8s  %9s\n", "preset", "estimator",
                "parameter error", "torque error", "position error", "95% cover", "sigma/", "diverged", "seconds");
  out += line;
  std::snprintf(line, sizeof line, "%-6s  %-9s  %10s %10s %10s  %10s %10s  %15s  %9s  %8s  %8s  %9s\n", "", "",
                "mean", "std", "median", "mean", "std", "mean (trials)", "", "spread", "", "mean");
  out += line;
  for (const BenchmarkSummary& s : result.summary) {
    char coverage[32];
    if (std::isfinite(s.coverage_95)) {
      std::snprintf(coverage, sizeof coverage, "%.1f%%", 100.0 * s.coverage_95);
    } else {
      std::snprintf(coverage, sizeof coverage, "-");
    }
    char ratio[32];
    if (std::isfinite(s.sigma_ratio)) {
      std::snprintf(ratio, sizeof ratio, "%.3g", s.sigma_ratio);
    } else {
      std::snprintf(ratio, sizeof ratio, "-");
    }
    char position[40];
    if (s.position_trials > 0) {
      std::snprintf(position, sizeof position, "%10.4g %4s", s.position_error.mean,
                    ("(" + std::to_string(s.position_trials) + ")").c_str());
    } else {
      std::snprintf(position, sizeof position, "%10s %4s", "-", "(0)");
    }
    std::snprintf(line, sizeof line,
                  "%-6s  %-9s  %10.4g %10.3g %10.4g  %10.4g %10.3g  %s  %9s  %8s  %4d/%-3d  %9.3g\n",
                  std::string(kNoisePresetNames.Name(s.preset)).c_str(), std::string(ToString(s.estimator)).c_str(),
                  s.parameter_error.mean, s.parameter_error.std, s.parameter_error.median, s.torque_error.mean,
                  s.torque_error.std, position, coverage, ratio, s.diverged, s.trials, s.seconds.mean);
    out += line;
  }
  out += "\nparameter error: |b - b_true| / ((|b| + |b_true|)/2) over the base parameters; torque error: "
         "|tau_hat - tau| / |tau| on the trial's log;\nposition error: |q - q_sim| / |q|, "
         "the closed loop re-simulated with the estimate, over the trials where that runs (the estimate a mechanism);\n95% cover: base parameters within 1.96 sigma of the truth; "
         "sigma/spread: median over the base parameters of RMS(sigma) / std(b) over the trials;\n"
         "diverged: error above 50x OLS's on the trial, or failed\n";
  return out;
}

}  // namespace idbench
