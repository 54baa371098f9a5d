#include "idbench/workbench/commands/benchmark_command.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <stdexcept>
#include <thread>

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

// What every trial shares: the model, the truth, the identify options.
struct BenchmarkSetup {
  const RobotModel* model = nullptr;
  const BenchmarkOptions* options = nullptr;
  Eigen::VectorXd beta_true;
};

// One estimator on a trial's prepared log, as `identify` runs it.
BenchmarkEstimate Estimate(const BenchmarkSetup& setup, IdentifyOptions identify, const PreparedLog& prepared,
                           TorqueEstimator estimator) {
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
  const BenchmarkEstimate ols = Estimate(setup, identify, prepared, TorqueEstimator::kOls);
  for (TorqueEstimator estimator : options.estimators) {
    BenchmarkEstimate estimate =
        estimator == TorqueEstimator::kOls ? ols : Estimate(setup, identify, prepared, estimator);
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

// The index of a trial in the whole run: presets in the run's order, then trials.
long RunIndex(const BenchmarkResult& result, NoisePreset preset, int trial) {
  const auto at = std::find(result.presets.begin(), result.presets.end(), preset);
  return static_cast<long>(at - result.presets.begin()) * result.trials + trial;
}

// JSON numbers: NaN as null (nlohmann writes doubles in their shortest
// round-trip form, so they read back bit for bit).
nlohmann::ordered_json Number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}
nlohmann::ordered_json Numbers(const Eigen::VectorXd& values) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (double v : values) out.push_back(Number(v));
  return out;
}
nlohmann::ordered_json StatisticJson(const BenchmarkStatistic& s) {
  return {{"mean", Number(s.mean)}, {"std", Number(s.std)}, {"median", Number(s.median)}};
}

// Reading benchmark.json back: each accessor throws "source: field: what".
class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + field + ": " + what);
  }
  const nlohmann::json& At(const nlohmann::json& j, const std::string& key, const std::string& field) const {
    if (!j.is_object() || !j.contains(key)) Fail(field, "missing");
    return j.at(key);
  }
  double Double(const nlohmann::json& j, const std::string& field) const {
    if (j.is_null()) return kNaN;
    if (!j.is_number()) Fail(field, "expected a number or null");
    return j.get<double>();
  }
  std::string String(const nlohmann::json& j, const std::string& field) const {
    if (!j.is_string()) Fail(field, "expected a string");
    return j.get<std::string>();
  }
  long Integer(const nlohmann::json& j, const std::string& field) const {
    if (!j.is_number_integer()) Fail(field, "expected an integer");
    return j.get<long>();
  }
  template <typename Enum, std::size_t N>
  Enum Name(const nlohmann::json& j, const EnumNames<Enum, N>& names, const std::string& field) const {
    Enum value{};
    std::string why;
    if (!names.Parse(String(j, field), &value, &why)) Fail(field, why);
    return value;
  }

 private:
  std::string source_;
};

}  // namespace

BenchmarkResult RunBenchmark(const RobotModel& model, const BenchmarkOptions& options,
                             const BenchmarkProgress& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  // The inputs every trial reads, checked once before any trial runs.
  ReadControllerFile(options.controller, model.n_dof());
  LoadTrajectoryArg(options.trajectory, model, BuiltinMotionOptions{});
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
  BenchmarkSetup setup{&model, &options, result.beta_true};

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
      std::vector<double> parameter, torque, coverage, seconds;
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
        coverage.push_back(estimate.coverage_95);
        kept.push_back(&estimate);
      }
      s.sigma_ratio = SigmaRatio(kept, result->beta_true.size());
      s.parameter_error = Statistic(parameter);
      s.torque_error = Statistic(torque);
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
  std::snprintf(line, sizeof line, "%-6s  %-9s  %32s  %21s  %9s  %8s  %8s  %9s\n", "preset", "estimator",
                "parameter error", "torque error", "95% cover", "sigma/", "diverged", "seconds");
  out += line;
  std::snprintf(line, sizeof line, "%-6s  %-9s  %10s %10s %10s  %10s %10s  %9s  %8s  %8s  %9s\n", "", "", "mean",
                "std", "median", "mean", "std", "", "spread", "", "mean");
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
    std::snprintf(line, sizeof line,
                  "%-6s  %-9s  %10.4g %10.3g %10.4g  %10.4g %10.3g  %9s  %8s  %4d/%-3d  %9.3g\n",
                  std::string(kNoisePresetNames.Name(s.preset)).c_str(), std::string(ToString(s.estimator)).c_str(),
                  s.parameter_error.mean, s.parameter_error.std, s.parameter_error.median, s.torque_error.mean,
                  s.torque_error.std, coverage, ratio, s.diverged, s.trials, s.seconds.mean);
    out += line;
  }
  out += "\nparameter error: |b - b_true| / ((|b| + |b_true|)/2) over the base parameters; torque error: "
         "|tau_hat - tau| / |tau| on the trial's log;\n95% cover: base parameters within 1.96 sigma of the truth; "
         "sigma/spread: median over the base parameters of RMS(sigma) / std(b) over the trials;\n"
         "diverged: error above 50x OLS's on the trial, or failed\n";
  return out;
}

std::string FormatBenchmarkJson(const BenchmarkResult& result) {
  nlohmann::ordered_json j;
  j["robot"] = result.robot;
  j["trajectory"] = result.trajectory;
  j["controller"] = result.controller;
  j["friction"] = result.friction;
  std::vector<std::string> estimators, presets;
  for (TorqueEstimator e : result.estimators) estimators.emplace_back(ToString(e));
  for (NoisePreset p : result.presets) presets.emplace_back(kNoisePresetNames.Name(p));
  j["estimators"] = estimators;
  j["presets"] = presets;
  j["trials"] = result.trials;
  j["seed"] = result.seed;
  if (result.shard_count > 1) j["shard"] = std::to_string(result.shard_index) + "/" + std::to_string(result.shard_count);
  j["parameter_error"] = "|b - b_true| / ((|b| + |b_true|) / 2)";
  j["divergence_factor"] = kDivergenceFactor;
  j["base_parameter_names"] = result.base_parameter_names;
  j["beta_true"] = std::vector<double>(result.beta_true.data(), result.beta_true.data() + result.beta_true.size());
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (const BenchmarkSummary& s : result.summary) {
    results.push_back({{"estimator", std::string(ToString(s.estimator))},
                       {"preset", std::string(kNoisePresetNames.Name(s.preset))},
                       {"trials", s.trials},
                       {"parameter_error", StatisticJson(s.parameter_error)},
                       {"torque_error", StatisticJson(s.torque_error)},
                       {"coverage_95", Number(s.coverage_95)},
                       {"sigma_ratio", Number(s.sigma_ratio)},
                       {"diverged", s.diverged},
                       {"seconds", StatisticJson(s.seconds)}});
  }
  j["results"] = results;
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const BenchmarkTrial& trial : result.trials_run) {
    nlohmann::ordered_json estimates = nlohmann::ordered_json::array();
    for (const BenchmarkEstimate& e : trial.estimates) {
      estimates.push_back({{"estimator", std::string(ToString(e.estimator))},
                           {"parameter_error", Number(e.parameter_error)},
                           {"torque_error", Number(e.torque_error)},
                           {"coverage_95", Number(e.coverage_95)},
                           {"diverged", e.diverged},
                           {"seconds", Number(e.seconds)},
                           {"message", e.message},
                           {"beta", Numbers(e.beta)},
                           {"sigma", Numbers(e.sigma)}});
    }
    trials.push_back({{"preset", std::string(kNoisePresetNames.Name(trial.preset))},
                      {"trial", trial.trial},
                      {"seed", trial.seed},
                      {"estimates", estimates}});
  }
  j["trial_values"] = trials;
  return j.dump(2) + "\n";
}

BenchmarkResult ParseBenchmarkJson(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument(source + ": not JSON: " + e.what());
  }
  const JsonReader r(source);
  BenchmarkResult out;
  out.robot = r.String(r.At(j, "robot", "robot"), "robot");
  out.trajectory = r.String(r.At(j, "trajectory", "trajectory"), "trajectory");
  out.controller = r.String(r.At(j, "controller", "controller"), "controller");
  for (const auto& term : r.At(j, "friction", "friction")) out.friction.push_back(r.String(term, "friction"));
  for (const auto& name : r.At(j, "estimators", "estimators")) {
    out.estimators.push_back(r.Name(name, kTorqueEstimatorNames, "estimators"));
  }
  for (const auto& name : r.At(j, "presets", "presets")) {
    out.presets.push_back(r.Name(name, kNoisePresetNames, "presets"));
  }
  out.trials = static_cast<int>(r.Integer(r.At(j, "trials", "trials"), "trials"));
  if (out.trials < 1 || out.trials > BenchmarkOptions::kMaxTrials) r.Fail("trials", "out of range");
  out.seed = static_cast<unsigned>(r.Integer(r.At(j, "seed", "seed"), "seed"));
  if (j.contains("shard")) {
    const std::string shard = r.String(j["shard"], "shard");
    if (std::sscanf(shard.c_str(), "%d/%d", &out.shard_index, &out.shard_count) != 2 || out.shard_count < 1 ||
        out.shard_index < 0 || out.shard_index >= out.shard_count) {
      r.Fail("shard", "expected K/N with 0 <= K < N, got '" + shard + "'");
    }
  }
  for (const auto& name : r.At(j, "base_parameter_names", "base_parameter_names")) {
    out.base_parameter_names.push_back(r.String(name, "base_parameter_names"));
  }
  const auto& beta = r.At(j, "beta_true", "beta_true");
  out.beta_true.resize(static_cast<Eigen::Index>(beta.size()));
  for (size_t k = 0; k < beta.size(); ++k) out.beta_true[static_cast<Eigen::Index>(k)] = r.Double(beta[k], "beta_true");
  const auto& trials = r.At(j, "trial_values", "trial_values");
  if (!trials.is_array()) r.Fail("trial_values", "expected an array");
  for (size_t t = 0; t < trials.size(); ++t) {
    const std::string field = "trial_values[" + std::to_string(t) + "]";
    BenchmarkTrial trial;
    trial.preset = r.Name(r.At(trials[t], "preset", field + ".preset"), kNoisePresetNames, field + ".preset");
    trial.trial = static_cast<int>(r.Integer(r.At(trials[t], "trial", field + ".trial"), field + ".trial"));
    trial.seed = static_cast<unsigned>(r.Integer(r.At(trials[t], "seed", field + ".seed"), field + ".seed"));
    if (std::find(out.presets.begin(), out.presets.end(), trial.preset) == out.presets.end() || trial.trial < 0 ||
        trial.trial >= out.trials) {
      r.Fail(field, "not a trial of this run (its presets, trials 0 to " + std::to_string(out.trials - 1) + ")");
    }
    const auto& estimates = r.At(trials[t], "estimates", field + ".estimates");
    if (estimates.size() != out.estimators.size()) {
      r.Fail(field + ".estimates", "expected " + std::to_string(out.estimators.size()) + " (one per estimator), got " +
                                       std::to_string(estimates.size()));
    }
    for (size_t e = 0; e < estimates.size(); ++e) {
      const std::string at = field + ".estimates[" + std::to_string(e) + "]";
      const auto& x = estimates[e];
      BenchmarkEstimate estimate;
      estimate.estimator = r.Name(r.At(x, "estimator", at + ".estimator"), kTorqueEstimatorNames, at + ".estimator");
      if (estimate.estimator != out.estimators[e]) r.Fail(at + ".estimator", "not the run's estimator in this place");
      estimate.parameter_error = r.Double(r.At(x, "parameter_error", at), at + ".parameter_error");
      estimate.torque_error = r.Double(r.At(x, "torque_error", at), at + ".torque_error");
      estimate.coverage_95 = r.Double(r.At(x, "coverage_95", at), at + ".coverage_95");
      estimate.seconds = r.Double(r.At(x, "seconds", at), at + ".seconds");
      const auto& diverged = r.At(x, "diverged", at + ".diverged");
      if (!diverged.is_boolean()) r.Fail(at + ".diverged", "expected true or false");
      estimate.diverged = diverged.get<bool>();
      estimate.message = r.String(r.At(x, "message", at + ".message"), at + ".message");
      for (auto [key, vector] : {std::pair<const char*, Eigen::VectorXd*>{"beta", &estimate.beta},
                                 std::pair<const char*, Eigen::VectorXd*>{"sigma", &estimate.sigma}}) {
        const auto& values = r.At(x, key, at + "." + key);
        if (!values.is_array()) r.Fail(at + "." + key, "expected an array");
        vector->resize(static_cast<Eigen::Index>(values.size()));
        for (size_t k = 0; k < values.size(); ++k) {
          (*vector)[static_cast<Eigen::Index>(k)] = r.Double(values[k], at + "." + key);
        }
      }
      trial.estimates.push_back(std::move(estimate));
    }
    out.trials_run.push_back(std::move(trial));
  }
  SummarizeBenchmark(&out);
  return out;
}

BenchmarkResult MergeBenchmarkResults(const std::vector<BenchmarkResult>& parts,
                                      const std::vector<std::string>& sources) {
  if (parts.empty() || parts.size() != sources.size()) {
    throw std::invalid_argument("merge: expected at least one benchmark result, each with its source");
  }
  const BenchmarkResult& first = parts.front();
  BenchmarkResult out = first;
  out.shard_index = 0;
  out.shard_count = 1;
  out.trials_run.clear();
  // Every part must be of the same run.
  for (size_t i = 1; i < parts.size(); ++i) {
    const BenchmarkResult& p = parts[i];
    auto differs = [&](const std::string& field) {
      throw std::invalid_argument(sources[i] + ": " + field + ": not the same as in " + sources[0] +
                                  " (the shards of one run must share every option but the shard)");
    };
    if (p.robot != first.robot) differs("robot");
    if (p.trajectory != first.trajectory) differs("trajectory");
    if (p.controller != first.controller) differs("controller");
    if (p.friction != first.friction) differs("friction");
    if (p.estimators != first.estimators) differs("estimators");
    if (p.presets != first.presets) differs("presets");
    if (p.trials != first.trials) differs("trials");
    if (p.seed != first.seed) differs("seed");
    if (p.base_parameter_names != first.base_parameter_names) differs("base_parameter_names");
    if (p.beta_true.size() != first.beta_true.size() ||
        !std::equal(p.beta_true.begin(), p.beta_true.end(), first.beta_true.begin())) {
      differs("beta_true");
    }
  }
  // Every trial of the run exactly once, put back in run order.
  std::map<long, std::pair<const BenchmarkTrial*, size_t>> by_index;
  for (size_t i = 0; i < parts.size(); ++i) {
    for (const BenchmarkTrial& trial : parts[i].trials_run) {
      const long index = RunIndex(first, trial.preset, trial.trial);
      const auto [at, inserted] = by_index.emplace(index, std::make_pair(&trial, i));
      if (!inserted) {
        throw std::invalid_argument(sources[i] + ": trial " + std::to_string(trial.trial) + " of preset " +
                                    std::string(kNoisePresetNames.Name(trial.preset)) + " is also in " +
                                    sources[at->second.second]);
      }
    }
  }
  const long total = static_cast<long>(first.presets.size()) * first.trials;
  for (long index = 0; index < total; ++index) {
    if (by_index.count(index) == 0) {
      throw std::invalid_argument(
          "merge: trial " + std::to_string(index % first.trials) + " of preset " +
          std::string(kNoisePresetNames.Name(first.presets[static_cast<size_t>(index / first.trials)])) +
          " is in none of the results given (a shard is missing)");
    }
    out.trials_run.push_back(*by_index[index].first);
  }
  SummarizeBenchmark(&out);
  return out;
}

}  // namespace idbench
