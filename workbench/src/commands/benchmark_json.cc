// benchmark.json: writing a run's result, reading it back, and merging the
// shards of one run into the whole (benchmark_command.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/workbench/commands/benchmark_command.h"

namespace idbench {
namespace {

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
    if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
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
  j["position_error"] = "|Q - Q_sim(b)| / |Q| (the closed loop re-simulated with b)";
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
                       {"position_error", StatisticJson(s.position_error)},
                       {"position_error_trials", s.position_trials},
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
                           {"position_error", Number(e.position_error)},
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
      estimate.position_error = r.Double(r.At(x, "position_error", at), at + ".position_error");
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
