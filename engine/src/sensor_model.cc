#include "idbench/engine/sensor_model.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace idbench {
namespace {

// 0 (white) or within (0, rate_hz/2]: a band above the Nyquist frequency
// would be white at that rate.
bool TorqueNoiseBandwidthIsValid(double bandwidth_hz, double rate_hz, std::string* why) {
  if (bandwidth_hz == 0.0) return true;
  if (!(bandwidth_hz > 0.0) || !std::isfinite(bandwidth_hz) || !(bandwidth_hz <= 0.5 * rate_hz)) {
    if (why) {
      char text[160];
      std::snprintf(text, sizeof(text), "tau_noise_bandwidth_hz: expected 0 (white) or a band in (0, %.6g] Hz (half "
                    "the sample rate), got %.6g", 0.5 * rate_hz, bandwidth_hz);
      *why = text;
    }
    return false;
  }
  return true;
}

}  // namespace

int SensorOptions::StepsPerSample(double dt) const {
  return static_cast<int>(std::lround(1.0 / (rate_hz * dt)));
}

bool SensorOptions::IsValid(int n_dof, double dt, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) return fail("rate must be > 0 Hz, got " + std::to_string(rate_hz));
  const double k = 1.0 / (rate_hz * dt);
  if (k < 1.0 - 1e-9 || std::abs(k - std::round(k)) > 1e-6 * k) {
    return fail("rate " + std::to_string(rate_hz) + " Hz must divide the simulation rate " +
                std::to_string(1.0 / dt) + " Hz by a whole number");
  }
  if (!(q_resolution >= 0.0) || !std::isfinite(q_resolution))
    return fail("encoder resolution must be >= 0 rad, got " + std::to_string(q_resolution));
  if (!(q_noise >= 0.0) || !std::isfinite(q_noise)) return fail("position noise must be >= 0 rad");
  if (tau_noise.size() > 1 && static_cast<int>(tau_noise.size()) != n_dof) {
    return fail("torque noise needs 1 or " + std::to_string(n_dof) + " values, got " +
                std::to_string(tau_noise.size()));
  }
  for (double s : tau_noise) {
    if (!(s >= 0.0) || !std::isfinite(s)) return fail("torque noise must be >= 0 N m, got " + std::to_string(s));
  }
  if (!TorqueNoiseBandwidthIsValid(tau_noise_bandwidth_hz, rate_hz, why)) return false;
  return true;
}

bool ApplyNoisePreset(NoisePreset preset, SensorOptions* options, std::string* why) {
  if (preset == NoisePreset::kNone) return true;
  if (options->q_noise != 0.0 || !options->tau_noise.empty()) {
    if (why) *why = "noise_preset: sets the position and torque noise (q_noise, tau_noise): give one or the other";
    return false;
  }
  constexpr double kDegree = M_PI / 180.0;
  options->q_noise = (preset == NoisePreset::kLow ? 1e-4 : 1e-2) * kDegree;
  options->tau_noise = {preset == NoisePreset::kLow ? 0.05 : 0.10};
  return true;
}

TorqueNoise::TorqueNoise(const std::vector<double>& sigma, int n_dof, double bandwidth_hz, double rate_hz) {
  std::string why;
  if (!TorqueNoiseBandwidthIsValid(bandwidth_hz, rate_hz, &why)) throw std::invalid_argument(why);
  if (n_dof < 1 || (sigma.size() != 1 && sigma.size() != static_cast<size_t>(n_dof))) {
    throw std::invalid_argument("tau_noise: expected 1 or " + std::to_string(n_dof) + " values, got " +
                                std::to_string(sigma.size()));
  }
  sigma_ = sigma.size() == 1 ? std::vector<double>(static_cast<size_t>(n_dof), sigma[0]) : sigma;
  state_.assign(sigma_.size(), 0.0);
  started_.assign(sigma_.size(), false);
  if (bandwidth_hz > 0.0) {
    a_ = std::exp(-2.0 * M_PI * bandwidth_hz / rate_hz);
    innovation_ = std::sqrt(1.0 - a_ * a_);
  }
}

double TorqueNoise::Next(int joint, double standard_normal) {
  const size_t j = static_cast<size_t>(joint);
  double& x = state_.at(j);
  if (!started_[j]) {
    started_[j] = true;
    x = sigma_[j] * standard_normal;
  } else {
    x = a_ * x + sigma_[j] * innovation_ * standard_normal;
  }
  return x;
}

SensorSampler::SensorSampler(const SensorOptions& options, int n_dof, double dt)
    : options_(options), n_dof_(n_dof), rng_(options.seed) {
  std::string why;
  if (!options.IsValid(n_dof, dt, &why)) throw std::invalid_argument("sensor model: " + why);
  if (!options.tau_noise.empty()) {
    tau_noise_.emplace(options.tau_noise, n_dof, options.tau_noise_bandwidth_hz, options.rate_hz);
  }
}

void SensorSampler::MeasureQ(const Eigen::VectorXd& q_true, Eigen::Ref<Eigen::VectorXd> q_measured) {
  for (Eigen::Index j = 0; j < q_true.size(); ++j) {
    double q = q_true[j];
    if (options_.q_noise > 0.0) q += options_.q_noise * normal_(rng_);
    if (options_.q_resolution > 0.0) q = options_.q_resolution * std::round(q / options_.q_resolution);
    q_measured[j] = q;
  }
}

void SensorSampler::MeasureTau(const Eigen::VectorXd& tau, Eigen::Ref<Eigen::VectorXd> tau_measured) {
  const std::vector<double>& sigma = options_.tau_noise;
  for (Eigen::Index j = 0; j < tau.size(); ++j) {
    const double s = sigma.empty() ? 0.0 : sigma.size() == 1 ? sigma[0] : sigma[static_cast<size_t>(j)];
    tau_measured[j] = tau[j] + (s > 0.0 ? tau_noise_->Next(static_cast<int>(j), normal_(rng_)) : 0.0);
  }
}

JointLog SensorSampler::SizedLog(int n_samples) const {
  JointLog out;
  out.t.resize(n_samples);
  out.q.resize(n_samples, n_dof_);
  out.tau.resize(n_samples, n_dof_);
  if (options_.record_derivatives) {
    out.qd.resize(n_samples, n_dof_);
    out.qdd.resize(n_samples, n_dof_);
  }
  return out;
}

JointLog Measure(const SimulationLog& log, const SensorOptions& options) {
  if (log.steps.empty()) throw std::invalid_argument("sensor model: the simulation log is empty");
  const int n_dof = static_cast<int>(log.steps.front().q.size());
  SensorSampler sensors(options, n_dof, log.dt);
  const int k = options.StepsPerSample(log.dt);
  const int n_samples = static_cast<int>((log.steps.size() + static_cast<size_t>(k) - 1) / static_cast<size_t>(k));

  JointLog out = sensors.SizedLog(n_samples);
  Eigen::VectorXd q(n_dof), tau(n_dof);
  for (int s = 0; s < n_samples; ++s) {
    const LogStep& step = log.steps[static_cast<size_t>(s) * static_cast<size_t>(k)];
    out.t[s] = step.t;
    sensors.MeasureQ(step.q, q);
    sensors.MeasureTau(step.tau, tau);
    out.q.row(s) = q.transpose();
    out.tau.row(s) = tau.transpose();
    if (options.record_derivatives) {
      out.qd.row(s) = step.qd.transpose();
      out.qdd.row(s) = step.qdd.transpose();
    }
  }
  return out;
}

}  // namespace idbench
