#include "idbench/engine/sensor_model.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace idbench {

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
  return true;
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
      out.tau(s, j) = step.tau[j] + (sigma > 0.0 ? sigma * normal(rng) : 0.0);
    }
    if (options.record_derivatives) {
      out.qd.row(s) = step.qd.transpose();
      out.qdd.row(s) = step.qdd.transpose();
    }
  }
  return out;
}

}  // namespace idbench
