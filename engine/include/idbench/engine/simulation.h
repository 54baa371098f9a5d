// A simulated identification experiment: Bullet tracks a reference motion
// with computed torques from the project's inverse dynamics, and every step is
// recorded with the quantities the identifiers use, all of one instant.
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
  // The classical Runge–Kutta step is stable for the loop's double pole at −ω
  // while ω·dt < 2.78; keep a wide margin.
  static constexpr double kMaxBandwidthTimesDt = 0.5;
  static constexpr double kMinDt = 1e-9;         // Bullet skips steps below its epsilon
  static constexpr double kMaxSteps = 1e6;       // the log keeps every step (~5 kB each)

  bool IsValid(std::string* why) const;
};

// Simulates round(duration/dt) steps from the reference's state at t = 0 and
// logs each step's start t = n·dt. The state x = (q, qd) advances by the
// classical fourth-order Runge–Kutta step, ẋ = (qd, qdd), whose four
// accelerations are Bullet's forward dynamics (BulletSimulation::
// Accelerations) under the computed torque of that stage's time and state:
// the controller acts continuously, and q is the integral of qd to O(dt⁴)
// (semi-implicit Euler, which Bullet steps with, leaves q half a step ahead of
// qd: the log's q and τ out of phase by O(dt), enough to bias an
// identification that differentiates q). Each logged step holds the first
// stage: q, qd, the torque, Bullet's acceleration under it and its joint
// feedback, so that τ = RNEA(q, qd, qdd) + AddJointDynamicsTorque and the hinge
// wrenches hold at that instant (to Bullet's agreement with the RNEA, ~1e-10).
// Throws std::invalid_argument if the options are invalid or the reference
// does not match the model.
SimulationLog Simulate(const RobotModel& model, const Trajectory& reference,
                       const SimulationOptions& options);

}  // namespace idbench
