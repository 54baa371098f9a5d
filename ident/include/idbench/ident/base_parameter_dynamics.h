// Forward dynamics of a base-parameter estimate β, from the regressor alone
// (no Bullet, no physical bodies needed): the torque W_b(q, q̇, q̈) β is
// linear in q̈, so with h(q, q̇) = W_b(q, q̇, 0) β and M(q) the coefficients
// of q̈ (ComputeJointSpaceInertia of β spread over the standard parameters),
// q̈ = M⁻¹ (τ − h). What the closed-loop estimators (IV, DIDIM) simulate.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

class BaseParameterDynamics {
 public:
  // Keeps references to model, friction and base (they must outlive it).
  // Throws std::invalid_argument unless beta has base.n_base() entries.
  BaseParameterDynamics(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                        const Eigen::VectorXd& beta);

  // q̈ [rad/s²] at (q, q̇) under the joint torques τ [N m]. Throws
  // std::runtime_error when M(q) of β is not positive definite there (an
  // estimate that is no mechanism).
  void Accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                     Eigen::VectorXd* qdd);

 private:
  const RobotModel& model_;
  const FrictionModel& friction_;
  Eigen::VectorXd pi_;  // β at the independent standard indices, 0 elsewhere: Y π = W_b β
  RobotData data_;
  Eigen::MatrixXd M_;
  Eigen::VectorXd zero_, h_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

}  // namespace idbench
