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
  const int n = model.n_dof();
  zero_ = Eigen::VectorXd::Zero(n);
  unit_ = Eigen::VectorXd::Zero(n);
  M_.resize(n, n);
}

void BaseParameterDynamics::Accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                          const Eigen::VectorXd& tau, Eigen::VectorXd* qdd) {
  const int n = model_.n_dof();
  // h(q, q̇) and the gravity-only g(q) = W_b(q, 0, 0) β.
  ComputeJointTorqueRegressor(model_, friction_, q, qd, zero_, &data_, &Y_);
  h_.noalias() = Y_ * pi_;
  ComputeJointTorqueRegressor(model_, friction_, q, zero_, zero_, &data_, &Y_);
  g_.noalias() = Y_ * pi_;
  // M(q) column by column.
  for (int i = 0; i < n; ++i) {
    unit_.setZero();
    unit_[i] = 1.0;
    ComputeJointTorqueRegressor(model_, friction_, q, zero_, unit_, &data_, &Y_);
    M_.col(i).noalias() = Y_ * pi_;
    M_.col(i) -= g_;
  }
  ldlt_.compute(M_);
  if (ldlt_.info() != Eigen::Success || !ldlt_.isPositive() || (ldlt_.vectorD().array() <= 0.0).any()) {
    throw std::runtime_error("the estimate's mass matrix is not positive definite");
  }
  *qdd = ldlt_.solve(tau - h_);
}

}  // namespace idbench
