// A simulated identification experiment: Bullet tracks a reference motion
// with computed torques from the project's inverse dynamics, and every step is
// recorded with the quantities the identifiers use.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/bullet_simulation.h"
#include "idbench/engine/quaternion.h"
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

  bool IsValid(std::string* why) const;
};

// Kinematics of one link at one step, as the per-body identifier reads it.
struct BodySample {
  QuaternionRates quaternion;                           // Λ, Λ', Λ''
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();        // angular velocity, body frame [rad/s]
  Eigen::Vector3d wd_B = Eigen::Vector3d::Zero();       // angular acceleration, body frame [rad/s²]
  Eigen::Vector3d a_WBcm_W = Eigen::Vector3d::Zero();   // centroid acceleration [m/s²]
};

// State at the start of step n (t = n·dt) and what happened during the step.
struct LogStep {
  double t = 0.0;        // [s]
  Eigen::VectorXd q;     // [rad]
  Eigen::VectorXd qd;    // [rad/s]
  Eigen::VectorXd qdd;   // (qd_{n+1} − qd_n)/dt [rad/s²]
  Eigen::VectorXd tau;   // applied joint torques [N m]
  std::vector<BodySample> body;    // per link, from kinematics at (q, qd, qdd)
  std::vector<HingeWrench> hinge;  // per link, Bullet's joint feedback
};

struct SimulationLog {
  std::string robot;
  double dt = 0.0;
  std::vector<LogStep> steps;

  // Index of the step nearest to time t, or -1 if t is outside the log.
  int StepAt(double t) const;
};

// Simulates round(duration/dt) steps from the reference's state at t = 0.
// Throws std::invalid_argument if the options are invalid or the reference
// does not match the model.
SimulationLog Simulate(const RobotModel& model, const Trajectory& reference,
                       const SimulationOptions& options);

}  // namespace idbench
