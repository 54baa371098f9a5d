#include "idbench/ident/total_least_squares.h"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <limits>

#include "linear_fit_internal.h"

namespace idbench {

LinearFit SolveTls(const StackedFactors& factors) {
  // OLS first: its rank, the identifiable parameters, cond and the variance
  // inflation (properties of W, the same for any estimator).
  LinearFit fit = SolveOls(factors);
  const int p = factors.n_parameters;
  const int r = fit.rank;
  const double n_equations = static_cast<double>(factors.n_samples()) * factors.n_dof();
  const Eigen::MatrixXd T = CombinedFactor(factors, Eigen::VectorXd::Ones(factors.n_dof()));
  const Eigen::MatrixXd R = T.topLeftCorner(p, p).triangularView<Eigen::Upper>();
  const Eigen::VectorXd z = T.col(p).head(p);
  const double rho = T(p, p);
  Eigen::VectorXd D;
  const Eigen::MatrixXd RD = internal::UnitColumns(R, &D);

  // The directions OLS resolves: all (V_r = I), or the leading right
  // singular vectors of R D.
  Eigen::MatrixXd V_r = Eigen::MatrixXd::Identity(p, p);
  if (r < p) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(RD, Eigen::ComputeFullV);
    V_r = svd.matrixV().leftCols(r);
  }
  const Eigen::MatrixXd A = RD * V_r;  // (p × r)
  const double tau_norm = T.col(p).norm();
  const double d_tau = tau_norm > 0.0 ? 1.0 / tau_norm : 1.0;

  // The SVD of T diag(D V_r, d_τ): (p + 1) × (r + 1).
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(p + 1, r + 1);
  M.topLeftCorner(p, r) = A;
  M.col(r).head(p) = d_tau * z;
  M(p, r) = d_tau * rho;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullV);
  const Eigen::VectorXd v = svd.matrixV().col(r);
  const double s = svd.singularValues()[r];
  // v_{r+1} = 0: no change of τ alone can make the equations exact (a
  // nongeneric problem, Van Huffel & Vandewalle §3.4); and if the two
  // smallest singular values coincide the solution is not unique.
  if (!(std::abs(v[r]) > 1e-12)) {
    fit.solve.converged = false;
    fit.solve.message = "no total-least-squares solution (the smallest singular vector of [W τ] has no τ "
                        "component): beta is the OLS estimate";
    return fit;
  }
  const Eigen::VectorXd gamma = -v.head(r) / (v[r] * d_tau);
  fit.beta = D.asDiagonal() * (V_r * gamma);

  // The bread G = D V_r (AᵀA − s² I)⁻¹ V_rᵀ D (WᵀW − s² D⁻² restricted to
  // the resolved directions, inverted).
  Eigen::MatrixXd H = A.transpose() * A;
  H.diagonal().array() -= s * s;
  const Eigen::MatrixXd B = D.asDiagonal() * V_r;
  const Eigen::MatrixXd G = B * H.ldlt().solve(B.transpose());
  // The scores at β̂ sum to Wᵀ(τ − W β̂) = Rᵀ(z − R β̂) ≠ 0 (TLS is not
  // orthogonal to the residual): that sum, spread evenly over the samples, is
  // taken off each (s² D⁻² β̂ / n in exact arithmetic).
  const Eigen::VectorXd e_top = z - R * fit.beta;
  fit.score_offset = -(R.transpose() * e_top) / static_cast<double>(factors.n_samples());
  const double s2 = (e_top.squaredNorm() + rho * rho) / (n_equations - r);
  fit.gram_inverse = G;
  fit.covariance = s2 * G * (R.transpose() * R) * G;
  fit.covariance = 0.5 * (fit.covariance + fit.covariance.transpose()).eval();
  fit.sigma = fit.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int k = 0; k < p; ++k) {
    if (!fit.identifiable[static_cast<size_t>(k)]) fit.sigma[k] = std::numeric_limits<double>::infinity();
  }
  fit.sigma_white = fit.sigma;
  fit.rel_sigma_percent = 100.0 * fit.sigma.cwiseQuotient(fit.beta.cwiseAbs());
  fit.joint_rms = JointResidualNorms(factors, fit.beta) / std::sqrt(static_cast<double>(factors.n_samples()));
  fit.joint_sigma = fit.joint_rms;
  char text[200];
  std::snprintf(text, sizeof(text),
                "closed form (SVD of the column-scaled [W tau]); smallest singular value %.3g of %.3g", s,
                svd.singularValues()[0]);
  fit.solve.message = text;
  return fit;
}

LinearFit SolveTls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  return SolveTls(FactorStackedRows(W, tau, n_dof));
}

}  // namespace idbench
