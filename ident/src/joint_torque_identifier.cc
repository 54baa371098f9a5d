#include "idbench/ident/joint_torque_identifier.h"

#include <stdexcept>

namespace idbench {

const char* ToString(TorqueEstimator estimator) {
  switch (estimator) {
    case TorqueEstimator::kOls: return "ols";
    case TorqueEstimator::kWls: return "wls";
    case TorqueEstimator::kPhysicallyConsistent: return "pc";
  }
  return "?";
}

std::optional<TorqueEstimator> ParseTorqueEstimator(const std::string& name) {
  for (TorqueEstimator e : {TorqueEstimator::kOls, TorqueEstimator::kWls, TorqueEstimator::kPhysicallyConsistent}) {
    if (name == ToString(e)) return e;
  }
  return std::nullopt;
}

Eigen::MatrixXd StackBaseRegressor(const RobotModel& model, const FrictionModel& friction,
                                   const BaseParameters& base, const JointLog& log) {
  const int n = model.n_dof();
  if (log.n_dof() != n || log.tau.cols() != n || log.tau.rows() != log.n_samples()) {
    throw std::invalid_argument("joint log has " + std::to_string(log.n_dof()) + " joints, robot '" +
                                model.name() + "' has " + std::to_string(n));
  }
  if (!log.has_derivatives()) {
    throw std::invalid_argument("joint log has no qd/qdd: estimate them first (filtering, signal_filter.h)");
  }
  Eigen::MatrixXd W(static_cast<Eigen::Index>(log.n_samples()) * n, base.n_base());
  RobotData data(model);
  Eigen::MatrixXd Y;
  Eigen::VectorXd q(n), qd(n), qdd(n);
  for (int s = 0; s < log.n_samples(); ++s) {
    q = log.q.row(s).transpose();
    qd = log.qd.row(s).transpose();
    qdd = log.qdd.row(s).transpose();
    ComputeJointTorqueRegressor(model, friction, q, qd, qdd, &data, &Y);
    for (int k = 0; k < base.n_base(); ++k) {
      W.block(static_cast<Eigen::Index>(s) * n, k, n, 1) = Y.col(base.independent[static_cast<size_t>(k)]);
    }
  }
  return W;
}

Eigen::VectorXd StackTorques(const JointLog& log) {
  // Row-major flattening of (n_samples × n_dof): sample by sample.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tau = log.tau;
  return Eigen::Map<const Eigen::VectorXd>(tau.data(), tau.size());
}

JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const JointLog& log,
                                              const JointTorqueOptions& options) {
  JointTorqueIdentification out;
  out.base = ComputeBaseParameters(model, options.friction, options.base);
  out.standard_names = StandardParameterNames(model, options.friction);
  const Eigen::VectorXd pi_model = StandardParameters(model, options.friction);
  out.beta_model = out.base.combination * pi_model;
  const Eigen::MatrixXd W = StackBaseRegressor(model, options.friction, out.base, log);
  const Eigen::VectorXd tau = StackTorques(log);
  if (W.rows() <= W.cols()) {
    throw std::invalid_argument("joint log has " + std::to_string(log.n_samples()) + " samples (" +
                                std::to_string(W.rows()) + " equations) for " + std::to_string(W.cols()) +
                                " base parameters; record more samples");
  }
  out.linear = options.estimator == TorqueEstimator::kWls ? SolveWls(W, tau, model.n_dof())
                                                          : SolveOls(W, tau, model.n_dof());
  out.beta = out.linear.beta;
  out.joint_rms = out.linear.joint_rms;
  out.consistent = SolvePhysicallyConsistent(W, tau, out.base, model.n_links(), out.linear.beta, pi_model,
                                             options.consistent);
  if (options.estimator == TorqueEstimator::kPhysicallyConsistent) {
    out.beta = out.consistent.beta;
    out.joint_rms = JointRms(W * out.beta - tau, model.n_dof());
  }
  return out;
}

TorquePrediction PredictTorques(const RobotModel& model, const FrictionModel& friction,
                                const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log) {
  const Eigen::VectorXd tau = StackTorques(log);
  const Eigen::VectorXd r = StackBaseRegressor(model, friction, base, log) * beta - tau;
  TorquePrediction out;
  out.joint_rms = JointRms(r, model.n_dof());
  out.relative_error = r.norm() / tau.norm();
  return out;
}

}  // namespace idbench
