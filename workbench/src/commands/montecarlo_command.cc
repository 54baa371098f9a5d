#include "idbench/workbench/commands/montecarlo_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <stdexcept>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/engine/resource_limits.h"
#include "idbench/engine/sensor_model.h"
#include "idbench/engine/simulation.h"
#include "idbench/ident/residual_covariance.h"
#include "number_format.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench {
namespace {

// The half-width of a normal 95 % interval in σ.
constexpr double kInterval95 = 1.96;

// Noise-free joint log of a motion over its duration, sampled at rate_hz.
JointLog SimulateNoiseFree(const RobotModel& model, const Trajectory& motion, double dt, double rate_hz) {
  SimulationOptions sim;
  sim.dt = dt;
  sim.duration = motion.duration();
  SensorOptions sensors;
  sensors.rate_hz = rate_hz;
  return Measure(Simulate(model, motion, sim), sensors);
}

// "Monte-Carlo: N trials, ..." without its newline; the noise's band and the
// filter path when not the defaults.
std::string Headline(const MonteCarloReport& report) {
  char line[512];
  std::snprintf(line, sizeof(line), "Monte-Carlo: %d trials, %d samples of '%s' (held out: '%s'), %d base parameters, WLS",
                report.trials, report.samples, report.trajectory.c_str(), report.held_out.c_str(), report.base.n_base());
  std::string out = line;
  if (!report.record_derivatives) out += ", qd and qdd from the filtered q";
  if (report.tau_noise_bandwidth_hz > 0.0) out += ", torque noise coloured to " + Shortest(report.tau_noise_bandwidth_hz) + " Hz";
  return out;
}

// The errors, the worst σ ratio and the coverage: four lines.
std::string Errors(const MonteCarloReport& report) {
  char line[640];
  std::snprintf(line, sizeof(line),
                "mean |dbeta|/|beta|: %.4g (predicted %.4g)\n"
                "worst empirical/predicted sigma: %.3f (parameter %d)\n"
                "95%% intervals holding the truth: %.1f%% (sigma by batch means; white-residual sigma: %.1f%%)\n"
                "held-out torque relative error: %.4g (noise alone: %.4g)\n",
                report.mean_relative_error, report.predicted_relative_error, 1.0 + report.worst_sigma_ratio,
                report.worst_sigma_index + 1, 100.0 * report.coverage, 100.0 * report.coverage_white,
                report.mean_held_out_error, report.held_out_noise_floor);
  return line;
}

// Fresh noise for a log's stacked torques (row = sample·n_dof + joint), drawn
// row by row from `rng`: white draws are those of earlier versions.
Eigen::VectorXd StackedNoise(const MonteCarloReport& report, Eigen::Index n_samples, int n_dof, double rate_hz,
                             std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  TorqueNoise noise(report.tau_noise, n_dof, report.tau_noise_bandwidth_hz, rate_hz);
  Eigen::VectorXd out(n_samples * n_dof);
  for (Eigen::Index r = 0; r < out.size(); ++r) out[r] = noise.Next(static_cast<int>(r % n_dof), normal(*rng));
  return out;
}

// FormatMonteCarloTables and FormatMonteCarloJson need the statistics.
void CheckCompleted(const MonteCarloReport& report) {
  if (report.status != MonteCarloStatus::kCompleted) {
    throw std::logic_error("montecarlo: no statistics to format: " + report.message);
  }
}

}  // namespace

std::string MonteCarloReport::BriefReport() const {
  if (status != MonteCarloStatus::kCompleted) return Headline(*this) + "\n" + message + "\n";
  return Headline(*this) + "\n" + Errors(*this);
}

std::vector<double> DefaultTorqueNoise(int n_dof) {
  std::vector<double> sigma(static_cast<size_t>(std::max(n_dof, 0)), 0.05);
  for (size_t j = 0; j < sigma.size() && j < 3; ++j) sigma[j] = 0.5;
  return sigma;
}

std::vector<double> TorqueNoiseOrDefault(const std::vector<double>& tau_noise, int n_dof) {
  if (tau_noise.empty()) return DefaultTorqueNoise(n_dof);
  if (tau_noise.size() != 1 && tau_noise.size() != static_cast<size_t>(n_dof)) {
    throw std::invalid_argument("tau_noise: expected 1 or " + std::to_string(n_dof) + " values (one per joint), got " +
                                std::to_string(tau_noise.size()));
  }
  return tau_noise;
}

bool MonteCarloOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (trials < 2 || trials > kMaxTrials) {
    return fail("trials: must be in [2, " + std::to_string(kMaxTrials) + "], got " + std::to_string(trials));
  }
  if (samples < 2) return fail("samples: must be >= 2, got " + std::to_string(samples));
  if (!(duration > 0.0) || !std::isfinite(duration)) return fail("duration: must be > 0 s");
  for (double s : tau_noise) {
    if (!(s > 0.0) || !std::isfinite(s)) return fail("tau_noise: every value must be > 0 N m");
  }
  if (!(tau_noise_bandwidth_hz >= 0.0) || !std::isfinite(tau_noise_bandwidth_hz)) {
    return fail("tau_noise_bandwidth_hz: expected 0 (white) or a band > 0 Hz, got " + Shortest(tau_noise_bandwidth_hz));
  }
  std::string filter_why;
  if (!record_derivatives && !filter.IsValid(&filter_why)) return fail("filter: " + filter_why);
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  std::string out_why;  // --out is optional here
  if (!out_dir.empty() && !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

void CheckRegressorSamples(const std::string& option, double samples, int n_dof) {
  const double n = n_dof;
  CheckFitsInMemory(option, samples, "samples", 8.0 * (2.0 * (6.0 * n) * (14.0 * n) + 2.0 * (1.0 + 4.0 * n)),
                    "two logs and their regressor rows");
}

MonteCarloReport RunMonteCarlo(const RobotModel& model, const MonteCarloOptions& options) {
  const BuiltinMotionOptions builtin{.duration = options.duration, .paper_qdd = 0.5};
  return RunMonteCarlo(model, options, *LoadTrajectoryArg(options.trajectory, model, builtin));
}

MonteCarloReport RunMonteCarlo(const RobotModel& model, const MonteCarloOptions& options, const Trajectory& motion) {
  const int n = model.n_dof();
  CheckRegressorSamples("samples", options.samples, n);
  const BuiltinMotionOptions builtin{.duration = options.duration, .paper_qdd = 0.5};
  const std::unique_ptr<Trajectory> held_motion = LoadTrajectoryArg(options.held_out, model, builtin);
  SensorOptions sensors;
  sensors.rate_hz = options.samples / motion.duration();
  sensors.tau_noise = TorqueNoiseOrDefault(options.tau_noise, n);
  sensors.tau_noise_bandwidth_hz = options.tau_noise_bandwidth_hz;
  std::string why;
  // The log rate samples/duration must divide the simulation rate: name
  // --samples (not --tau-noise) and the steps it must divide.
  const double per_sample = motion.duration() / options.dt / options.samples;
  if (per_sample < 1.0 - 1e-9 || std::abs(per_sample - std::round(per_sample)) > 1e-6 * per_sample) {
    throw std::invalid_argument("samples: " + std::to_string(options.samples) + " samples over the " +
                                Shortest(motion.duration()) + " s motion fall every " + Format("%.4g", per_sample) +
                                " simulation steps of " + Shortest(options.dt) +
                                " s; they must fall on whole steps (samples must divide the " +
                                std::to_string(std::lround(motion.duration() / options.dt)) + " steps)");
  }
  if (!sensors.IsValid(n, options.dt, &why)) {
    throw std::invalid_argument(why.rfind("tau_noise", 0) == 0 ? why : "tau_noise: " + why);
  }
  // The filter path: the filter must fit the log's rate.
  std::optional<ParallelFilter> filter;
  if (!options.record_derivatives) {
    if (!(options.filter.cutoff_hz < 0.5 * sensors.rate_hz / options.filter.decimation)) {
      throw std::invalid_argument("filter.cutoff_hz: expected below half the log's rate after decimation, " +
                                  Shortest(0.5 * sensors.rate_hz / options.filter.decimation) + " Hz (" +
                                  std::to_string(options.samples) + " samples over " + Shortest(motion.duration()) +
                                  " s), got " + Shortest(options.filter.cutoff_hz) + " Hz");
    }
    filter = ParallelFilter{options.filter, sensors.rate_hz};
    filter->filter.filter_tau = false;  // the torques are filtered with the regressor (parallel filtering)
  }
  // 1. One noise-free experiment and one held-out, and the fixed regressors.
  const FrictionModel friction = ParseFrictionTerms(options.friction, nullptr).value_or(FrictionModel{});
  const JointLog log = SimulateNoiseFree(model, motion, options.dt, sensors.rate_hz);
  const JointLog held = SimulateNoiseFree(model, *held_motion, options.dt, sensors.rate_hz);
  MonteCarloReport report;
  report.trajectory = options.trajectory;
  report.held_out = options.held_out;
  report.trials = options.trials;
  report.samples = options.samples;
  report.tau_noise = sensors.tau_noise;
  report.tau_noise_bandwidth_hz = options.tau_noise_bandwidth_hz;
  report.record_derivatives = options.record_derivatives;
  report.log = log;
  report.base = ComputeBaseParameters(model, friction);
  report.beta_true = report.base.combination * StandardParameters(model, friction);
  // The identification's equations: from the exact states, or as identify
  // builds them from t, q, τ (qd, qdd from the filtered q; W and τ filtered
  // alike, the ends trimmed). The filter is linear, so a trial's torques are
  // the noise-free ones plus its noise filtered the same way.
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  if (filter) {
    // qd, qdd from the filtered q over the whole log; the trimming and
    // decimation act once, on the equations (as identify's streamed filter).
    LogFilterOptions derivatives = filter->filter;
    derivatives.decimation = 1;
    derivatives.trim_s = 0.0;
    const JointLog logged = ProcessJointLog(log.t, log.q, log.tau, derivatives);
    StackEquations(model, friction, report.base, logged, filter, &W, &tau);
  } else {
    W = StackBaseRegressor(model, friction, report.base, log);
    tau = StackTorques(log);
  }
  report.n_equation_samples = static_cast<int>(W.rows() / n);
  auto trial_torques = [&](std::mt19937_64* rng) {
    Eigen::VectorXd noise = StackedNoise(report, log.n_samples(), n, sensors.rate_hz, rng);
    if (filter) {
      Eigen::MatrixXd rows = noise;
      ParallelFilterStackedRows(filter->filter, filter->sample_rate_hz, n, &rows);
      noise = rows.col(0);
    }
    return Eigen::VectorXd(tau + noise);
  };
  const Eigen::MatrixXd W_held = StackBaseRegressor(model, friction, report.base, held);
  const Eigen::VectorXd tau_held = StackTorques(held);

  // 2. Trials: fresh torque noise on both logs, WLS with σ from the residual, errors.
  const int p = report.base.n_base();
  std::mt19937_64 rng(options.seed);
  Eigen::MatrixXd estimates(p, options.trials);
  Eigen::VectorXd sigma_sum = Eigen::VectorXd::Zero(p), sigma_white_sum = Eigen::VectorXd::Zero(p);
  Eigen::MatrixXd cov_sum = Eigen::MatrixXd::Zero(p, p);
  long covered = 0, covered_white = 0;
  for (int trial = 0; trial < options.trials; ++trial) {
    const Eigen::VectorXd measured_tau = trial_torques(&rng);
    LinearFit fit = SolveWls(W, measured_tau, n);
    if (fit.rank < p) {  // no estimate from this motion: no statistics
      report.status = MonteCarloStatus::kNotExcited;
      report.message = "montecarlo: the motion does not excite every base parameter (W has rank " +
                       std::to_string(fit.rank) + " of " + std::to_string(p) +
                       "); choose a richer `trajectory` (see compare)";
      return report;
    }
    ApplyStackedScoreCovariance(W, measured_tau, n, &fit);
    estimates.col(trial) = fit.beta;
    sigma_sum += fit.sigma;
    sigma_white_sum += fit.sigma_white;
    cov_sum += fit.covariance;
    report.n_effective += fit.covariance_method.n_effective;
    const Eigen::ArrayXd error = (fit.beta - report.beta_true).cwiseAbs().array();
    covered += (error <= kInterval95 * fit.sigma.array()).count();
    covered_white += (error <= kInterval95 * fit.sigma_white.array()).count();
    report.mean_relative_error += (fit.beta - report.beta_true).norm() / report.beta_true.norm();
    const Eigen::VectorXd measured =
        tau_held + StackedNoise(report, held.n_samples(), n, sensors.rate_hz, &rng);
    report.mean_held_out_error += (W_held * fit.beta - measured).norm() / measured.norm();
    report.held_out_noise_floor += (W_held * report.beta_true - measured).norm() / measured.norm();
  }
  const double trials = options.trials;
  report.mean_relative_error /= trials;
  report.mean_held_out_error /= trials;
  report.held_out_noise_floor /= trials;
  report.n_effective /= trials;
  report.coverage = static_cast<double>(covered) / (trials * p);
  report.coverage_white = static_cast<double>(covered_white) / (trials * p);
  report.predicted_sigma = sigma_sum / trials;
  report.predicted_sigma_white = sigma_white_sum / trials;
  report.predicted_relative_error = std::sqrt((cov_sum / trials).trace()) / report.beta_true.norm();
  const Eigen::VectorXd mean = estimates.rowwise().mean();
  report.empirical_bias = mean - report.beta_true;
  report.empirical_sigma =
      ((estimates.colwise() - mean).rowwise().squaredNorm() / (trials - 1.0)).cwiseSqrt();
  const Eigen::VectorXd ratio = report.empirical_sigma.cwiseQuotient(report.predicted_sigma).array() - 1.0;
  report.worst_sigma_ratio = ratio.cwiseAbs().maxCoeff(&report.worst_sigma_index);
  return report;
}

std::string FormatMonteCarloTables(const MonteCarloOptions& options, const MonteCarloReport& report) {
  CheckCompleted(report);
  std::string out;
  char line[512];
  out += Headline(report) + "\n\n";
  std::snprintf(line, sizeof(line), "%4s  %14s  %12s  %12s  %7s  %12s  %s\n", "#", "true", "predicted σ", "empirical σ",
                "ratio", "bias/σ", "base parameter");
  out += line;
  const double sqrt_trials = std::sqrt(static_cast<double>(options.trials));
  for (int k = 0; k < report.base.n_base(); ++k) {
    std::snprintf(line, sizeof(line), "%4d  %14.6g  %12.4g  %12.4g  %7.3f  %12.3g  %s\n", k + 1, report.beta_true[k],
                  report.predicted_sigma[k], report.empirical_sigma[k],
                  report.empirical_sigma[k] / report.predicted_sigma[k],
                  report.empirical_bias[k] / (report.predicted_sigma[k] / sqrt_trials),
                  report.base.names[static_cast<size_t>(k)].c_str());
    out += line;
  }
  out += "\n" + Errors(report);
  return out;
}

std::string FormatMonteCarloJson(const MonteCarloOptions& options, const MonteCarloReport& report) {
  CheckCompleted(report);
  nlohmann::json j = {
      {"command", options.command_line},
      {"robot", options.robot},
      {"trials", options.trials},
      {"samples", options.samples},
      {"seed", options.seed},
      {"tau_noise", report.tau_noise},
      {"tau_noise_bandwidth_hz", report.tau_noise_bandwidth_hz},
      {"derivatives", report.record_derivatives ? "simulator" : "filtered_q"},
      {"sigma_method", ToKey(CovarianceMethod::kBatchMeans)},
      {"equation_samples", report.n_equation_samples},
      {"n_effective", report.n_effective},
      {"base_parameter_names", report.base.names},
      {"beta_true", ToStdVector(report.beta_true)},
      {"predicted_sigma", ToStdVector(report.predicted_sigma)},
      {"predicted_sigma_white", ToStdVector(report.predicted_sigma_white)},
      {"empirical_sigma", ToStdVector(report.empirical_sigma)},
      {"coverage", report.coverage},
      {"coverage_white", report.coverage_white},
      {"mean_relative_error", report.mean_relative_error},
      {"predicted_relative_error", report.predicted_relative_error},
      {"worst_sigma_ratio_deviation", report.worst_sigma_ratio},
      {"mean_held_out_relative_error", report.mean_held_out_error},
      {"held_out_noise_floor", report.held_out_noise_floor},
  };
  return j.dump(2) + "\n";
}

}  // namespace idbench
