#include "idbench/engine/sensor_model.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
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

JointLog Measure(const SimulationLog& log, const SensorOptions& options) {
  if (log.steps.empty()) throw std::invalid_argument("sensor model: the simulation log is empty");
  const int n_dof = static_cast<int>(log.steps.front().q.size());
  std::string why;
  if (!options.IsValid(n_dof, log.dt, &why)) throw std::invalid_argument("sensor model: " + why);
  const int k = options.StepsPerSample(log.dt);
  const int n_samples = static_cast<int>((log.steps.size() + static_cast<size_t>(k) - 1) / static_cast<size_t>(k));

  JointLog out;
  out.t.resize(n_samples);
  out.q.resize(n_samples, n_dof);
  out.tau.resize(n_samples, n_dof);
  if (options.record_derivatives) {
    out.qd.resize(n_samples, n_dof);
    out.qdd.resize(n_samples, n_dof);
  }
  // One generator, drawn in a fixed order (sample, then q before τ by joint).
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::optional<TorqueNoise> tau_noise;
  if (!options.tau_noise.empty()) {
    tau_noise.emplace(options.tau_noise, n_dof, options.tau_noise_bandwidth_hz, options.rate_hz);
  }
  for (int s = 0; s < n_samples; ++s) {
    const LogStep& step = log.steps[static_cast<size_t>(s) * static_cast<size_t>(k)];
    out.t[s] = step.t;
    for (int j = 0; j < n_dof; ++j) {
      double q = step.q[j];
      if (options.q_noise > 0.0) q += options.q_noise * normal(rng);
      if (options.q_resolution > 0.0) q = options.q_resolution * std::round(q / options.q_resolution);
      out.q(s, j) = q;
    }
    for (int j = 0; j < n_dof; ++j) {
      const double sigma = options.tau_noise.empty()      ? 0.0
                           : options.tau_noise.size() == 1 ? options.tau_noise[0]
                                                           : options.tau_noise[static_cast<size_t>(j)];
      out.tau(s, j) = step.tau[j] + (sigma > 0.0 ? tau_noise->Next(j, normal(rng)) : 0.0);
    }
    if (options.record_derivatives) {
      out.qd.row(s) = step.qd.transpose();
      out.qdd.row(s) = step.qdd.transpose();
    }
  }
  return out;
}

}  // namespace idbench
