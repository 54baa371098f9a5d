#include "link_equations.h"

#include <Eigen/SVD>
#include <stdexcept>

#include "idbench/ident/linear_estimator.h"
#include "idbench/logs/signal_filter.h"

namespace idbench::internal {

Eigen::MatrixXd StackLinkEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters* base,
                                   int link, const JointLog& motion, const Eigen::MatrixXd& extra,
                                   const std::optional<ParallelFilter>& parallel_filter, const std::string& which) {
  const int n = model.n_dof();
  const JointLog& m = motion;
  const int n_samples = m.n_samples();
  const auto fail = [&](const std::string& what) { throw std::invalid_argument(which + " log: " + what); };
  if (m.n_dof() != n || m.qd.rows() != n_samples || m.qdd.rows() != n_samples || m.qd.cols() != n ||
      m.qdd.cols() != n) {
    fail("expected q, qd, qdd of " + std::to_string(n) + " joints for " + std::to_string(n_samples) +
         " samples (robot '" + model.name() + "')");
  }
  const Eigen::Index n_rows = static_cast<Eigen::Index>(n_samples) * n;
  if (extra.rows() != n_rows) {
    fail("expected " + std::to_string(n_rows) + " stacked rows of torques or currents, got " +
         std::to_string(extra.rows()));
  }
  if (link < 0 || link >= model.n_links()) {
    throw std::invalid_argument("expected a link index in [0, " + std::to_string(model.n_links()) + "), got " +
                                std::to_string(link));
  }
  const int n_base = base ? base->n_base() : 0;
  const int link_first = link * kInertialParametersPerLink;
  Eigen::MatrixXd rows(n_rows, n_base + kInertialParametersPerLink + extra.cols());
  RobotData data(model);
  Eigen::MatrixXd Y;
  Eigen::VectorXd q(n), qd(n), qdd(n);
  for (int s = 0; s < n_samples; ++s) {
    q = m.q.row(s).transpose();
    qd = m.qd.row(s).transpose();
    qdd = m.qdd.row(s).transpose();
    ComputeJointTorqueRegressor(model, friction, q, qd, qdd, &data, &Y);
    const Eigen::Index r0 = static_cast<Eigen::Index>(s) * n;
    for (int k = 0; k < n_base; ++k) rows.block(r0, k, n, 1) = Y.col(base->independent[static_cast<size_t>(k)]);
    rows.block(r0, n_base, n, kInertialParametersPerLink) = Y.middleCols(link_first, kInertialParametersPerLink);
  }
  rows.rightCols(extra.cols()) = extra;
  if (parallel_filter) ParallelFilterStackedRows(parallel_filter->filter, parallel_filter->sample_rate_hz, n, &rows);
  return rows;
}

MinNormSolution SolveMinNorm(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const std::vector<std::string>& names) {
  const Eigen::Index p = A.cols();
  const Eigen::MatrixXd factor = CombinedFactor(A, b);
  const Eigen::MatrixXd R = factor.topLeftCorner(p, p);
  const Eigen::VectorXd z = factor.col(p).head(p);
  MinNormSolution out;
  out.ls = SolveLeastSquares(R, z, names);
  // SVD of the column-normalised R, truncated at the rank decided above; a
  // column that SolveLeastSquares counts as zero stays zero (normalised, its
  // rounding would take a rank slot).
  Eigen::VectorXd norms = R.colwise().norm();
  const double zero_norm = LeastSquaresOptions{}.zero_column_tolerance * (p > 0 ? norms.maxCoeff() : 0.0);
  Eigen::MatrixXd Rn = R;
  for (Eigen::Index c = 0; c < p; ++c) {
    if (norms[c] > zero_norm && norms[c] > 0.0) {
      Rn.col(c) /= norms[c];
    } else {
      norms[c] = 1.0;
      Rn.col(c).setZero();
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Rn, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const int rank = out.ls.rank;
  const Eigen::VectorXd inverse_sv = svd.singularValues().head(rank).cwiseInverse();
  out.pseudo_inverse_factor =
      norms.cwiseInverse().asDiagonal() * (svd.matrixV().leftCols(rank) * inverse_sv.asDiagonal());
  out.x = out.pseudo_inverse_factor * (svd.matrixU().leftCols(rank).transpose() * z);
  out.variance = out.pseudo_inverse_factor.rowwise().squaredNorm();
  out.residual2 = (R * out.x - z).squaredNorm() + factor(p, p) * factor(p, p);
  return out;
}

}  // namespace idbench::internal
