#include "idbench/ident/linear_estimator.h"

#include "idbench/ident/least_squares.h"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>
#include <string>

namespace idbench {
namespace {

void CheckSizes(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  if (W.rows() != tau.size() || n_dof <= 0 || W.rows() % n_dof != 0) {
    throw std::invalid_argument("least squares: W has " + std::to_string(W.rows()) + " rows, tau " +
                                std::to_string(tau.size()) + ", n_dof " + std::to_string(n_dof));
  }
  if (W.rows() <= W.cols()) {
    throw std::invalid_argument("least squares: " + std::to_string(W.rows()) + " equations for " +
                                std::to_string(W.cols()) + " parameters; need more samples");
  }
}

// OLS on (W, tau) with row weights already applied. W has full column rank
// (base parameters), so an unpivoted, blocked Householder QR serves; its R
// gives the covariance and cond(W) (= cond(R)) without another factorisation.
LinearFit Fit(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau) {
  LinearFit fit;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(W);
  const Eigen::Index p = W.cols();
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  fit.beta = R.triangularView<Eigen::Upper>().solve((qr.householderQ().transpose() * tau).head(p));
  const Eigen::VectorXd r = W * fit.beta - tau;
  const double dof = static_cast<double>(W.rows() - W.cols());
  const double s2 = r.squaredNorm() / dof;
  // (WᵀW)⁻¹ = R⁻¹ R⁻ᵀ.
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  fit.covariance = Rinv * Rinv.transpose() * s2;
  fit.sigma = fit.covariance.diagonal().cwiseSqrt();
  fit.rel_sigma_percent = 100.0 * fit.sigma.cwiseQuotient(fit.beta.cwiseAbs());
  fit.cond = ConditionNumber(R);
  return fit;
}

}  // namespace

Eigen::VectorXd JointRms(const Eigen::VectorXd& r, int n_dof) {
  const Eigen::Index n_samples = r.size() / n_dof;
  const Eigen::Map<const Eigen::MatrixXd> R(r.data(), n_dof, n_samples);
  return (R.rowwise().squaredNorm() / static_cast<double>(n_samples)).cwiseSqrt();
}

LinearFit SolveOls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  CheckSizes(W, tau, n_dof);
  LinearFit fit = Fit(W, tau);
  fit.joint_rms = JointRms(W * fit.beta - tau, n_dof);
  fit.joint_sigma = fit.joint_rms;
  return fit;
}

LinearFit SolveWls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  CheckSizes(W, tau, n_dof);
  // Per-joint noise from the OLS residuals, with the degrees of freedom shared
  // evenly among joints.
  const LinearFit ols = Fit(W, tau);
  const Eigen::VectorXd r = W * ols.beta - tau;
  const double n_samples = static_cast<double>(W.rows() / n_dof);
  const double per_joint_dof = (static_cast<double>(W.rows()) - static_cast<double>(W.cols())) / n_dof;
  Eigen::VectorXd sigma = (JointRms(r, n_dof).array().square() * n_samples / per_joint_dof).sqrt();
  const double floor = 1e-12 * std::max(1.0, sigma.maxCoeff());
  sigma = sigma.cwiseMax(floor);
  Eigen::MatrixXd Ww = W;
  Eigen::VectorXd tw = tau;
  for (Eigen::Index row = 0; row < W.rows(); ++row) {
    const double w = 1.0 / sigma[row % n_dof];
    Ww.row(row) *= w;
    tw[row] *= w;
  }
  LinearFit fit = Fit(Ww, tw);
  fit.joint_rms = JointRms(W * fit.beta - tau, n_dof);
  fit.joint_sigma = sigma;
  return fit;
}

}  // namespace idbench
