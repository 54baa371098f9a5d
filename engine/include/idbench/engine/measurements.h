// What a simulated (or measured) identification experiment records per step.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/quaternion.h"

namespace idbench {

// The wrench a hinge transmits from the parent onto its link, world axes.
struct HingeWrench {
  Eigen::Vector3d f_W = Eigen::Vector3d::Zero();     // force [N]
  Eigen::Vector3d m_Bo_W = Eigen::Vector3d::Zero();  // moment about the hinge point [N m]
};

// Kinematics of one link at one step, as the per-body identifier reads it.
struct BodySample {
  QuaternionRates quaternion;                           // Λ, Λ', Λ''
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();        // angular velocity, body frame [rad/s]
  Eigen::Vector3d wd_B = Eigen::Vector3d::Zero();       // angular acceleration, body frame [rad/s²]
  Eigen::Vector3d a_WBcm_W = Eigen::Vector3d::Zero();   // centroid acceleration [m/s²]
};

// The experiment at the start of step n (t = n·dt): every field of that one
// instant (Simulate).
struct LogStep {
  double t = 0.0;        // [s]
  Eigen::VectorXd q;     // [rad]
  Eigen::VectorXd qd;    // [rad/s]
  Eigen::VectorXd qdd;   // Bullet's forward dynamics at (q, qd) under the applied torque [rad/s²]
  Eigen::VectorXd tau;   // motor torques [N m]: rigid-body torque applied in Bullet + AddJointDynamicsTorque
  std::vector<BodySample> body;    // per link, from kinematics at (q, qd, qdd)
  std::vector<HingeWrench> hinge;  // per link, the joint feedback at (q, qd) under the applied torque
};

struct SimulationLog {
  std::string robot;
  double dt = 0.0;
  std::vector<LogStep> steps;

  // Index of the step nearest to time t, or -1 if t is outside the log.
  int StepAt(double t) const;
};

// A joint-space log, simulated or recorded on a real robot: what joint-torque
// identification reads. Rows are samples, columns joints.
struct JointLog {
  Eigen::VectorXd t;    // sample times [s] (n_samples), strictly increasing
  Eigen::MatrixXd q;    // joint positions [rad] (n_samples × n_dof)
  Eigen::MatrixXd qd;   // velocities [rad/s]; empty (0 × 0) when not recorded
  Eigen::MatrixXd qdd;  // accelerations [rad/s²]; empty when not recorded
  Eigen::MatrixXd tau;  // motor torques [N m]

  int n_samples() const { return static_cast<int>(t.size()); }
  int n_dof() const { return static_cast<int>(q.cols()); }
  bool has_derivatives() const { return qd.size() > 0 && qdd.size() > 0; }
};

}  // namespace idbench
