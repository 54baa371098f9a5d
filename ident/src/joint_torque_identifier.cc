#include "idbench/ident/joint_torque_identifier.h"

#include <cmath>
#include <stdexcept>

namespace idbench {

namespace {

TorquePrediction Predict(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, const Eigen::VectorXd& beta,
                         int n_dof) {
  const Eigen::VectorXd r = W * beta - tau;
  TorquePrediction out;
  out.joint_rms = JointRms(r, n_dof);
  out.relative_error = r.norm() / tau.norm();
  return out;
}

}  // namespace

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

void StackEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                    const JointLog& log, const std::optional<ParallelFilter>& filter, Eigen::MatrixXd* W,
                    Eigen::VectorXd* tau) {
  *W = StackBaseRegressor(model, friction, base, log);
  *tau = StackTorques(log);
  if (!filter) return;
  const int n = model.n_dof();
  const Eigen::Index n_samples = log.n_samples();
  const LogFilterOptions& f = filter->filter;
  const SosMatrix sos = DesignButterworthLowPass(f.order, f.cutoff_hz, filter->sample_rate_hz);
  // Per joint: the samples of that joint's rows, every column and τ alike.
  using Strided = Eigen::Map<Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  for (int j = 0; j < n; ++j) {
    Strided Wj(W->data() + j, n_samples, W->cols(), Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(W->rows(), n));
    Strided tj(tau->data() + j, n_samples, 1, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(tau->size(), n));
    Wj = FiltFilt(sos, Wj);
    tj = FiltFilt(sos, tj);
  }
  // Drop the transients at both ends, then keep every k-th sample.
  const double trim_s = f.trim_s < 0.0 ? 5.0 / f.cutoff_hz : f.trim_s;
  const Eigen::Index trim = static_cast<Eigen::Index>(std::ceil(trim_s * filter->sample_rate_hz - 1e-9));
  if (n_samples - 2 * trim < 1) {
    throw std::invalid_argument("joint log: " + std::to_string(n_samples) + " samples are too few to drop " +
                                std::to_string(trim) + " filter-transient samples at both ends");
  }
  std::vector<Eigen::Index> kept;
  for (Eigen::Index s = trim; s < n_samples - trim; s += f.decimation) kept.push_back(s);
  Eigen::MatrixXd W_kept(static_cast<Eigen::Index>(kept.size()) * n, W->cols());
  Eigen::VectorXd tau_kept(W_kept.rows());
  for (size_t k = 0; k < kept.size(); ++k) {
    W_kept.middleRows(static_cast<Eigen::Index>(k) * n, n) = W->middleRows(kept[k] * n, n);
    tau_kept.segment(static_cast<Eigen::Index>(k) * n, n) = tau->segment(kept[k] * n, n);
  }
  *W = std::move(W_kept);
  *tau = std::move(tau_kept);
}

JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const JointLog& log,
                                              const JointTorqueOptions& options) {
  JointTorqueIdentification out;
  out.base = ComputeBaseParameters(model, options.friction, options.base);
  out.standard_names = StandardParameterNames(model, options.friction);
  const Eigen::VectorXd pi_model = StandardParameters(model, options.friction);
  out.beta_model = out.base.combination * pi_model;
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model, options.friction, out.base, log, options.parallel_filter, &W, &tau);
  if (W.rows() <= W.cols()) {
    throw std::invalid_argument("joint log has " + std::to_string(W.rows() / model.n_dof()) + " usable samples (" +
                                std::to_string(W.rows()) + " equations) for " + std::to_string(W.cols()) +
                                " base parameters; record more samples");
  }
  out.linear = options.estimator == TorqueEstimator::kWls ? SolveWls(W, tau, model.n_dof())
                                                          : SolveOls(W, tau, model.n_dof());
  out.beta = out.linear.beta;
  // Friction and rotor inertia are physical only when >= 0 (offsets are signed).
  PhysicallyConsistentOptions consistent = options.consistent;
  for (size_t c = 0; c < out.standard_names.size(); ++c) {
    const std::string& name = out.standard_names[c];
    if (name.rfind("Fv", 0) == 0 || name.rfind("Fc", 0) == 0 || name.rfind("Ia", 0) == 0) {
      consistent.nonnegative.push_back(static_cast<int>(c));
    }
  }
  out.consistent = SolvePhysicallyConsistent(W, tau, out.base, model.n_links(), out.linear.beta, pi_model,
                                             consistent);
  if (options.estimator == TorqueEstimator::kPhysicallyConsistent) out.beta = out.consistent.beta;
  out.fit = Predict(W, tau, out.beta, model.n_dof());
  out.model_fit = Predict(W, tau, out.beta_model, model.n_dof());
  return out;
}

TorquePrediction PredictTorques(const RobotModel& model, const JointTorqueOptions& options,
                                const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log) {
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model, options.friction, base, log, options.parallel_filter, &W, &tau);
  return Predict(W, tau, beta, model.n_dof());
}

}  // namespace idbench
