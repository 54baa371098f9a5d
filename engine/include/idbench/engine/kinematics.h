// Forward kinematics of a RobotModel: poses, velocities and accelerations of
// every link, in the world frame W.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench {

// Workspace for kinematics and dynamics; sized once from the model, then
// reused without allocation. Vectors are indexed by link.
struct RobotData {
  explicit RobotData(const RobotModel& model);

  // Written by ComputeKinematics.
  std::vector<Eigen::Matrix3d> R_WB;     // link orientation
  std::vector<Eigen::Vector3d> p_WBo_W;  // link origin = inboard hinge point [m]
  std::vector<Eigen::Vector3d> p_WBcm_W; // centre of mass [m]
  std::vector<Eigen::Vector3d> axis_W;   // hinge axis (unit)
  std::vector<Eigen::Vector3d> w_WB_W;   // angular velocity [rad/s]
  std::vector<Eigen::Vector3d> wd_WB_W;  // angular acceleration [rad/s²]
  std::vector<Eigen::Vector3d> v_WBo_W;  // velocity of the hinge point [m/s]
  std::vector<Eigen::Vector3d> a_WBo_W;  // acceleration of the hinge point [m/s²]
  std::vector<Eigen::Vector3d> a_WBcm_W; // centre-of-mass acceleration [m/s²]

  // Written by InverseDynamics (inverse_dynamics.h).
  std::vector<Eigen::Vector3d> f_PB_W;     // force the hinge transmits from parent P onto B [N]
  std::vector<Eigen::Vector3d> m_PB_Bo_W;  // moment it transmits, about the hinge point Bo [N m]
  Eigen::VectorXd tau;                     // joint torques [N m] (n_dof)
};

// Poses, velocities and accelerations of all links at (q, qd, qdd).
// Throws std::invalid_argument if a vector does not have n_dof entries.
void ComputeKinematics(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                       const Eigen::VectorXd& qdd, RobotData* data);

// Angular velocity / acceleration of link i expressed in its own frame B.
inline Eigen::Vector3d BodyAngularVelocity(const RobotData& data, int i) {
  return data.R_WB[static_cast<size_t>(i)].transpose() * data.w_WB_W[static_cast<size_t>(i)];
}
inline Eigen::Vector3d BodyAngularAcceleration(const RobotData& data, int i) {
  // d/dt(Rᵀw) = Rᵀẇ + (Rᵀw)×... = Rᵀẇ because ω × ω = 0.
  return data.R_WB[static_cast<size_t>(i)].transpose() * data.wd_WB_W[static_cast<size_t>(i)];
}

}  // namespace idbench
