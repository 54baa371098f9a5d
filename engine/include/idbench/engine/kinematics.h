// Forward kinematics of a RobotModel: poses, velocities and accelerations of
// every link, in the world frame W.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench {

// Poses, velocities and accelerations of every link, on a scalar type: double,
// or Adjoint (adjoint.h) for exact derivatives with respect to the joint state.
// Vectors are indexed by link.
template <typename Scalar>
struct KinematicsData {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  explicit KinematicsData(const RobotModel& model);

  std::vector<Matrix3> R_WB;     // link orientation
  std::vector<Vector3> p_WBo_W;  // link origin = inboard hinge point [m]
  std::vector<Vector3> p_WBcm_W; // centre of mass [m]
  std::vector<Vector3> axis_W;   // hinge axis (unit)
  std::vector<Vector3> w_WB_W;   // angular velocity [rad/s]
  std::vector<Vector3> wd_WB_W;  // angular acceleration [rad/s²]
  std::vector<Vector3> v_WBo_W;  // velocity of the hinge point [m/s]
  std::vector<Vector3> a_WBo_W;  // acceleration of the hinge point [m/s²]
  std::vector<Vector3> a_WBcm_W; // centre-of-mass acceleration [m/s²]
};

// Workspace for kinematics and dynamics; sized once from the model, then
// reused without allocation.
struct RobotData : KinematicsData<double> {
  explicit RobotData(const RobotModel& model);

  // Written by InverseDynamics (inverse_dynamics.h).
  std::vector<Eigen::Vector3d> f_PB_W;     // force the hinge transmits from parent P onto B [N]
  std::vector<Eigen::Vector3d> m_PB_Bo_W;  // moment it transmits, about the hinge point Bo [N m]
  Eigen::VectorXd tau;                     // joint torques [N m] (n_dof)
};

// The same on any scalar (instantiated for double and Adjoint).
template <typename Scalar>
void ComputeKinematicsT(const RobotModel& model, const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd, KinematicsData<Scalar>* data);

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
