// Sensors of a simulated experiment: what a robot controller would log.
// Positions come from quantising encoders with additive noise, torques from
// noisy current/torque sensing; velocities and accelerations are either the
// simulator's exact values (ideal sensing) or left out, as on a real robot,
// for the data processing (signal_filter.h) to estimate.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "idbench/engine/enum_names.h"
#include "idbench/engine/measurements.h"

namespace idbench {

struct SensorOptions {
  double rate_hz = 1000.0;        // sample rate; must be 1/(k·dt) for a whole k
  double q_resolution = 0.0;      // encoder quantum [rad]; 0 = none
  double q_noise = 0.0;           // σ of position noise [rad], before quantisation
  std::vector<double> tau_noise;  // σ of torque noise [N m]: none, one for all joints, or one per joint
  // Band of the torque noise [Hz]: 0 = white; else low-pass coloured to
  // this −3 dB cutoff with σ unchanged (TorqueNoise), in (0, rate_hz/2].
  double tau_noise_bandwidth_hz = 0.0;
  bool record_derivatives = true; // log the simulator's exact qd, qdd
  unsigned seed = 1;              // the noise is reproducible for a given seed

  // *why names the bad value; n_dof and dt are the robot's and simulation's.
  bool IsValid(int n_dof, double dt, std::string* why) const;
  // Decimation of the simulation steps: round(1 / (rate_hz · dt)).
  int StepsPerSample(double dt) const;
};

// BIRDy's noise levels (TUM-ICS/BIRDy, its Monte-Carlo benchmark): kLow
// position noise 1e-4° and torque noise 0.05 N m, kHigh 1e-2° and 0.10 N m.
enum class NoisePreset { kNone, kLow, kHigh };
inline constexpr EnumNames<NoisePreset, 3> kNoisePresetNames{"noise_preset", {"none", "low", "high"}};
// Sets q_noise [rad] and tau_noise (one for all joints) to the preset's;
// kNone leaves them. false with *why when the options already hold position
// or torque noise (a preset replaces both: one or the other).
bool ApplyNoisePreset(NoisePreset preset, SensorOptions* options, std::string* why);

// Torque noise of σ_j per joint, sample by sample: white, or coloured by a
// first-order low-pass of −3 dB cutoff f_c (the exact discretisation of an
// Ornstein–Uhlenbeck process at the sample rate f_s):
//   x_0 = σ e_0,   x_k = a x_{k−1} + σ √(1 − a²) e_k,   a = exp(−2π f_c / f_s),
// e_k standard normal draws, so every x_k has variance σ² (stationary from
// the first sample) and the autocorrelation at lag ℓ is a^ℓ. White (f_c = 0)
// is a = 0: x_k = σ e_k, the same numbers for the same draws.
class TorqueNoise {
 public:
  // sigma: one σ for all joints or one per joint [N m]; bandwidth_hz 0 or in
  // (0, rate_hz/2]. Throws std::invalid_argument naming tau_noise or
  // tau_noise_bandwidth_hz.
  TorqueNoise(const std::vector<double>& sigma, int n_dof, double bandwidth_hz, double rate_hz);

  // Joint j's noise at its next sample, from a standard normal draw.
  double Next(int joint, double standard_normal);
  // exp(−2π f_c / f_s): the correlation of consecutive samples (0 = white).
  double correlation() const { return a_; }

 private:
  std::vector<double> sigma_;  // per joint
  std::vector<double> state_;  // x_{k−1} per joint
  std::vector<bool> started_;
  double a_ = 0.0, innovation_ = 1.0;  // a, √(1 − a²)
};

// The sensors sample by sample: q through the encoders, then τ through the
// torque sensing, in this order at every sample, from one generator seeded
// with options.seed (Measure's numbers). A closed loop (closed_loop.h) reads
// q before its controller decides τ, so both draw the same noise.
class SensorSampler {
 public:
  // Throws std::invalid_argument as Measure when the options are not valid
  // for n_dof joints and the step dt [s].
  SensorSampler(const SensorOptions& options, int n_dof, double dt);
  // The measured positions of the true q (n_dof) [rad].
  void MeasureQ(const Eigen::VectorXd& q, Eigen::Ref<Eigen::VectorXd> q_measured);
  // The logged torques of the true τ (n_dof) [N m].
  void MeasureTau(const Eigen::VectorXd& tau, Eigen::Ref<Eigen::VectorXd> tau_measured);
  // A log of n_samples these sensors fill: t, q, τ, and qd, qdd when recorded.
  JointLog SizedLog(int n_samples) const;

 private:
  SensorOptions options_;
  int n_dof_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::optional<TorqueNoise> tau_noise_;
};

// Samples a simulation log through the sensors. Throws std::invalid_argument
// if the options are not valid for the log.
JointLog Measure(const SimulationLog& log, const SensorOptions& options);

}  // namespace idbench
