// Sensors of a simulated experiment: what a robot controller would log.
// Positions come from quantising encoders with additive noise, torques from
// noisy current/torque sensing; velocities and accelerations are either the
// simulator's exact values (ideal sensing) or left out, as on a real robot,
// for the data processing (signal_filter.h) to estimate.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/measurements.h"

namespace idbench {

struct SensorOptions {
  double rate_hz = 1000.0;        // sample rate; must be 1/(k·dt) for a whole k
  double q_resolution = 0.0;      // encoder quantum [rad]; 0 = none
  double q_noise = 0.0;           // σ of position noise [rad], before quantisation
  std::vector<double> tau_noise;  // σ of torque noise [N m]: none, one for all joints, or one per joint
  bool record_derivatives = true; // log the simulator's exact qd, qdd
  unsigned seed = 1;              // the noise is reproducible for a given seed

  // *why names the bad value; n_dof and dt are the robot's and simulation's.
  bool IsValid(int n_dof, double dt, std::string* why) const;
  // Decimation of the simulation steps: round(1 / (rate_hz · dt)).
  int StepsPerSample(double dt) const;
};

// Samples a simulation log through the sensors. Throws std::invalid_argument
// if the options are not valid for the log.
JointLog Measure(const SimulationLog& log, const SensorOptions& options);

}  // namespace idbench
