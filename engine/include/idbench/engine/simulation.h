// A simulated identification experiment: Bullet tracks a reference motion
// with computed torques from the project's inverse dynamics, and every step is
// recorded with the quantities the identifiers use.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/bullet_simulation.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"

namespace idbench {

struct SimulationOptions {
  double dt = 1e-3;        // step [s]
  double duration = 2.0;   // simulated time [s]; at most the trajectory's duration
  JointFeedbackMode feedback = JointFeedbackMode::kCorrected;
  // Computed-torque tracking: qdd_cmd = qdd_ref + 2ζω (qd_ref − qd) + ω² (q_ref − q),
  // critically damped (ζ = 1). 0 = pure feed-forward.
  double tracking_bandwidth = 20.0;  // ω [rad/s]
  // Semi-implicit Euler with this PD is stable for ω·dt below ~0.8; keep a margin.
  static constexpr double kMaxBandwidthTimesDt = 0.5;
  static constexpr double kMinDt = 1e-9;         // Bullet skips steps below its epsilon
  static constexpr double kMaxSteps = 1e6;       // the log keeps every step (~5 kB each)

  bool IsValid(std::string* why) const;
};

// Simulates round(duration/dt) steps from the reference's state at t = 0.
// Throws std::invalid_argument if the options are invalid or the reference
// does not match the model.
SimulationLog Simulate(const RobotModel& model, const Trajectory& reference,
                       const SimulationOptions& options);

}  // namespace idbench
