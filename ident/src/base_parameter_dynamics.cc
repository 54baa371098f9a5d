#include "idbench/ident/base_parameter_dynamics.h"

#include <stdexcept>
#include <string>

namespace idbench {

BaseParameterDynamics::BaseParameterDynamics(const RobotModel& model, const FrictionModel& friction,
                                             const BaseParameters& base, const Eigen::VectorXd& beta)
    : model_(model), friction_(friction), data_(model) {
  if (beta.size() != base.n_base()) {
    throw std::invalid_argument("BaseParameterDynamics: expected " + std::to_string(base.n_base()) +
                                " base parameters, got " + std::to_string(beta.size()));
  }
  pi_ = Eigen::VectorXd::Zero(base.combination.cols());
  for (int k = 0; k < base.n_base(); ++k) pi_[base.independent[static_cast<size_t>(k)]] = beta[k];
  zero_ = Eigen::VectorXd::Zero(model.n_dof());
}

void BaseParameterDynamics::Accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                          const Eigen::VectorXd& tau, Eigen::VectorXd* qdd) {
  // h(q, q̇) = W_b(q, q̇, 0) β, then M(q) of β from the same poses.
  ComputeJointTorqueOfParameters(model_, friction_, q, qd, zero_, pi_, &data_, &h_);
  ComputeJointSpaceInertia(model_, friction_, pi_, data_, &M_);
  ldlt_.compute(M_);
  if (ldlt_.info() != Eigen::Success || !ldlt_.isPositive() || (ldlt_.vectorD().array() <= 0.0).any()) {
    throw std::runtime_error("the estimate's mass matrix is not positive definite");
  }
  *qdd = ldlt_.solve(tau - h_);
}

}  // namespace idbench
