#include "idbench/ident/linear_estimator.h"

#include "idbench/ident/least_squares.h"
#include "householder_fold.h"
#include "linear_fit_internal.h"

#include <algorithm>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
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

constexpr double kInfinity = std::numeric_limits<double>::infinity();
using internal::kRankTolerance;

}  // namespace

namespace internal {

// R D with unit columns (D = 1/‖column‖), so that units do not decide the
// rank. A column below 1e-9 of the largest (as SolveLeastSquares: the data do
// not excite that parameter, e.g. a joint that does not move) is zero in R D,
// with D = 1.
Eigen::MatrixXd UnitColumns(const Eigen::MatrixXd& R, Eigen::VectorXd* D) {
  constexpr double kZeroColumn = 1e-9;
  const Eigen::VectorXd norms = R.colwise().norm().transpose();
  const double largest = norms.size() > 0 ? norms.maxCoeff() : 0.0;
  D->resize(norms.size());
  Eigen::MatrixXd RD = R;
  for (Eigen::Index k = 0; k < norms.size(); ++k) {
    const bool zero = !(norms[k] > kZeroColumn * largest);
    (*D)[k] = zero ? 1.0 : 1.0 / norms[k];
    if (zero) RD.col(k).setZero();
    else RD.col(k) *= (*D)[k];
  }
  return RD;
}

}  // namespace internal

namespace {

using internal::UnitColumns;

// ‖W_j β − τ_j‖ of one joint from its factor: ‖T [β_columns; −1]‖.
double JointResidualNorm(const JointRowFactor& f, const Eigen::VectorXd& beta) {
  const Eigen::Index c = static_cast<Eigen::Index>(f.columns.size());
  Eigen::VectorXd x(c + 1);
  for (Eigen::Index k = 0; k < c; ++k) x[k] = beta[f.columns[static_cast<size_t>(k)]];
  x[c] = -1.0;
  return (f.T.triangularView<Eigen::Upper>() * x).norm();
}

// Least squares over all joints' rows, joint j's weighted by weights[j], from
// their combined factor [R z; 0 ρ]: ‖W β − τ‖² = ‖R β − z‖² + ρ². Full rank:
//   β = R⁻¹ z,  (WᵀW)⁻¹ = R⁻¹ R⁻ᵀ,  cond(W) = cond(R).
// Otherwise, with R D = U Σ Vᵀ (D scales R's columns to unit norm, so that
// units do not decide the rank) and r singular values above
// kRankTolerance × the largest (a column below 1e-9 of the largest counted as
// zero): the minimum-norm solution β = D V_r Σ_r⁻¹ U_rᵀ z,
// covariance s² D V_r Σ_r⁻² V_rᵀ D; a parameter is identifiable iff its row
// of V_null, the rest of V, vanishes (as SolveLeastSquares).
LinearFit Fit(const StackedFactors& factors, const Eigen::VectorXd& weights) {
  const int p = factors.n_parameters;
  const double n_equations = static_cast<double>(factors.n_samples()) * factors.n_dof();
  if (n_equations <= p) {
    throw std::invalid_argument("least squares: " + std::to_string(static_cast<long long>(n_equations)) +
                                " equations for " + std::to_string(p) + " parameters; need more samples");
  }
  const Eigen::MatrixXd T = CombinedFactor(factors, weights);
  const Eigen::MatrixXd R = T.topLeftCorner(p, p).triangularView<Eigen::Upper>();
  const Eigen::VectorXd z = T.col(p).head(p);
  const Eigen::VectorXd norms = R.colwise().norm().transpose();
  Eigen::VectorXd D;
  const Eigen::MatrixXd RD = UnitColumns(R, &D);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(RD);  // singular values only, unless rank deficient
  int rank = 0;
  while (rank < p && svd.singularValues()[rank] > kRankTolerance * svd.singularValues()[0]) ++rank;

  LinearFit fit;
  fit.rank = rank;
  fit.identifiable.assign(static_cast<size_t>(p), true);
  double s2 = T(p, p) * T(p, p) / (n_equations - rank);
  Eigen::MatrixXd gram_inverse;  // (WᵀW)⁻¹, or the g-inverse of the minimum-norm estimator
  if (rank == p) {
    fit.beta = R.triangularView<Eigen::Upper>().solve(z);
    const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
    gram_inverse = Rinv * Rinv.transpose();
    fit.cond = ConditionNumber(R);
  } else {
    svd.compute(RD, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd& s = svd.singularValues();
    // ‖r‖² = ρ² plus the part of z no β can fit (in the rounding-level rows
    // of R that a dependent column leaves).
    s2 += (svd.matrixU().rightCols(p - rank).transpose() * z).squaredNorm() / (n_equations - rank);
    const auto V_r = svd.matrixV().leftCols(rank);
    const Eigen::MatrixXd V_null = svd.matrixV().rightCols(p - rank);
    const Eigen::VectorXd y = (svd.matrixU().leftCols(rank).transpose() * z).cwiseQuotient(s.head(rank));
    fit.beta = D.asDiagonal() * (V_r * y);
    const Eigen::MatrixXd B = D.asDiagonal() * V_r * s.head(rank).cwiseInverse().asDiagonal();
    gram_inverse = B * B.transpose();
    for (int k = 0; k < p; ++k) fit.identifiable[static_cast<size_t>(k)] = V_null.row(k).norm() <= 1e-6;
    fit.cond = kInfinity;
  }
  fit.covariance = gram_inverse * s2;
  fit.sigma = fit.covariance.diagonal().cwiseSqrt();
  fit.gram_inverse = gram_inverse;
  fit.row_weights = weights;
  fit.covariance_method.method = CovarianceMethod::kWhite;
  fit.covariance_method.n_samples = factors.n_samples();
  fit.covariance_method.n_effective = static_cast<double>(factors.n_samples());
  // (WᵀW)⁻¹_kk ‖W_k‖² with ‖W_k‖ = ‖R_k‖ (W = Q R).
  fit.variance_inflation = gram_inverse.diagonal().cwiseProduct(norms.cwiseAbs2());
  for (int k = 0; k < p; ++k) {
    if (!fit.identifiable[static_cast<size_t>(k)]) fit.sigma[k] = fit.variance_inflation[k] = kInfinity;
  }
  fit.sigma_white = fit.sigma;
  fit.rel_sigma_percent = 100.0 * fit.sigma.cwiseQuotient(fit.beta.cwiseAbs());
  // Unweighted residual RMS per joint (the same for every least-squares β).
  fit.joint_rms = JointResidualNorms(factors, fit.beta) / std::sqrt(static_cast<double>(factors.n_samples()));
  return fit;
}

}  // namespace

const char* ToString(CovarianceMethod method) {
  return method == CovarianceMethod::kBatchMeans ? "batch means" : "white";
}

const char* ToKey(CovarianceMethod method) {
  return method == CovarianceMethod::kBatchMeans ? "batch_means" : "white";
}

ParameterStatus ClassifyParameter(double beta, double sigma) {
  if (!std::isfinite(beta) || !std::isfinite(sigma)) return ParameterStatus::kNotIdentifiable;
  if (sigma <= kDeterminedSigmaPercent / 100.0 * std::abs(beta)) return ParameterStatus::kDetermined;
  if (std::abs(beta) > kZeroSigmas * sigma) return ParameterStatus::kPoor;
  return ParameterStatus::kIndistinguishableFromZero;
}

const char* ToString(ParameterStatus status) {
  switch (status) {
    case ParameterStatus::kDetermined: return "determined";
    case ParameterStatus::kPoor: return "poor";
    case ParameterStatus::kIndistinguishableFromZero: return "indistinguishable from zero";
    case ParameterStatus::kNotIdentifiable: return "not identifiable";
  }
  return "?";
}

StackedFactors::StackedFactors(int n_parameters_in, const std::vector<std::vector<int>>& columns_per_joint)
    : n_parameters(n_parameters_in) {
  for (const std::vector<int>& columns : columns_per_joint) {
    for (size_t k = 0; k < columns.size(); ++k) {
      if (columns[k] < 0 || columns[k] >= n_parameters || (k > 0 && columns[k] <= columns[k - 1])) {
        throw std::invalid_argument("stacked factors: expected ascending columns in [0, " +
                                    std::to_string(n_parameters) + "), got " + std::to_string(columns[k]));
      }
    }
    const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
    joints.push_back(JointRowFactor{columns, Eigen::MatrixXd::Zero(c + 1, c + 1), 0});
  }
}

void FoldJointRows(Eigen::Ref<Eigen::MatrixXd> rows, JointRowFactor* factor) {
  Eigen::MatrixXd& T = factor->T;
  if (rows.cols() != T.cols()) {
    throw std::invalid_argument("fold rows: expected " + std::to_string(T.cols()) + " columns, got " +
                                std::to_string(rows.cols()));
  }
  internal::FoldRowsIntoTriangle(T.data(), T.outerStride(), rows.data(), rows.outerStride(), rows.rows(),
                                 T.cols());
  factor->n_rows += rows.rows();
}

void MergeStackedFactors(const StackedFactors& other, StackedFactors* into) {
  if (other.n_parameters != into->n_parameters || other.joints.size() != into->joints.size()) {
    throw std::invalid_argument("merge factors: expected " + std::to_string(into->n_dof()) + " joints and " +
                                std::to_string(into->n_parameters) + " parameters, got " +
                                std::to_string(other.n_dof()) + " and " + std::to_string(other.n_parameters));
  }
  for (size_t j = 0; j < other.joints.size(); ++j) {
    JointRowFactor& f = into->joints[j];
    if (other.joints[j].columns != f.columns) {
      throw std::invalid_argument("merge factors: joint " + std::to_string(j + 1) + " has other columns");
    }
    const Eigen::Index n_rows = f.n_rows + other.joints[j].n_rows;  // T's rows stand for them
    Eigen::MatrixXd rows = other.joints[j].T;
    FoldJointRows(rows, &f);
    f.n_rows = n_rows;
  }
}

StackedFactors FactorStackedRows(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof,
                                 const RobustRowWeights* weights, IrlsPassRecord* residuals) {
  CheckSizes(W, tau, n_dof);
  const Eigen::Index n_samples = W.rows() / n_dof;
  using Strided = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  // Per joint, the columns that are non-zero somewhere in its rows.
  std::vector<std::vector<int>> columns(static_cast<size_t>(n_dof));
  for (int j = 0; j < n_dof; ++j) {
    const Strided Wj(W.data() + j, n_samples, W.cols(), Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(W.rows(), n_dof));
    for (int c = 0; c < W.cols(); ++c) {
      if ((Wj.col(c).array() != 0.0).any()) columns[static_cast<size_t>(j)].push_back(c);
    }
  }
  StackedFactors factors(static_cast<int>(W.cols()), columns);
  // Fold each joint's rows in blocks.
  constexpr Eigen::Index kBlock = 256;
  Eigen::MatrixXd rows;
  for (int j = 0; j < n_dof; ++j) {
    JointRowFactor& f = factors.joints[static_cast<size_t>(j)];
    const Eigen::Index c = static_cast<Eigen::Index>(f.columns.size());
    for (Eigen::Index s0 = 0; s0 < n_samples; s0 += kBlock) {
      const Eigen::Index m = std::min(kBlock, n_samples - s0);
      rows.resize(m, c + 1);
      for (Eigen::Index s = 0; s < m; ++s) {
        const Eigen::Index row = (s0 + s) * n_dof + j;
        for (Eigen::Index k = 0; k < c; ++k) rows(s, k) = W(row, f.columns[static_cast<size_t>(k)]);
        rows(s, c) = tau[row];
      }
      if (weights) {  // an IRLS pass: each row scaled by √w at its residual
        Eigen::VectorXd r(m);
        for (Eigen::Index s = 0; s < m; ++s) {
          const Eigen::Index row = (s0 + s) * n_dof + j;
          r[s] = tau[row] - W.row(row).dot(weights->beta);
        }
        if (residuals) residuals->AddRows(j, r, rows.leftCols(c), f.columns, *weights);
        for (Eigen::Index s = 0; s < m; ++s) rows.row(s) *= std::sqrt(weights->Weight(j, r[s]));
      }
      FoldJointRows(rows, &f);
    }
  }
  return factors;
}

Eigen::VectorXd JointRms(const Eigen::VectorXd& r, int n_dof) {
  const Eigen::Index n_samples = r.size() / n_dof;
  const Eigen::Map<const Eigen::MatrixXd> R(r.data(), n_dof, n_samples);
  return (R.rowwise().squaredNorm() / static_cast<double>(n_samples)).cwiseSqrt();
}

Eigen::VectorXd JointResidualNorms(const StackedFactors& factors, const Eigen::VectorXd& beta) {
  if (beta.size() != factors.n_parameters) {
    throw std::invalid_argument("joint residuals: expected " + std::to_string(factors.n_parameters) +
                                " parameters, got " + std::to_string(beta.size()));
  }
  Eigen::VectorXd norms(factors.n_dof());
  for (int j = 0; j < factors.n_dof(); ++j) norms[j] = JointResidualNorm(factors.joints[static_cast<size_t>(j)], beta);
  return norms;
}

Eigen::MatrixXd CombinedFactor(const StackedFactors& factors, const Eigen::VectorXd& weights) {
  if (weights.size() != factors.n_dof()) {
    throw std::invalid_argument("combined factor: expected " + std::to_string(factors.n_dof()) +
                                " joint weights, got " + std::to_string(weights.size()));
  }
  // The joints' factors, weighted and scattered into the full column space,
  // folded into one.
  const int p = factors.n_parameters;
  Eigen::Index n_rows = 0;
  for (const JointRowFactor& f : factors.joints) n_rows += f.T.rows();
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(n_rows, p + 1);
  Eigen::Index r0 = 0;
  for (size_t j = 0; j < factors.joints.size(); ++j) {
    const JointRowFactor& f = factors.joints[j];
    const Eigen::Index c = static_cast<Eigen::Index>(f.columns.size());
    const double weight = weights[static_cast<Eigen::Index>(j)];
    for (Eigen::Index k = 0; k < c; ++k) {
      rows.col(f.columns[static_cast<size_t>(k)]).segment(r0, c + 1) = weight * f.T.col(k);
    }
    rows.col(p).segment(r0, c + 1) = weight * f.T.col(c);
    r0 += c + 1;
  }
  std::vector<int> all(static_cast<size_t>(p));
  for (int k = 0; k < p; ++k) all[static_cast<size_t>(k)] = k;
  StackedFactors total(p, {all});
  FoldJointRows(rows, &total.joints.front());
  return std::move(total.joints.front().T);
}

Eigen::MatrixXd CombinedFactor(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau) {
  return CombinedFactor(FactorStackedRows(W, tau, 1), Eigen::VectorXd::Ones(1));
}

LinearFit SolveOls(const StackedFactors& factors) {
  LinearFit fit = Fit(factors, Eigen::VectorXd::Ones(factors.n_dof()));
  fit.joint_sigma = fit.joint_rms;
  fit.solve.message = "closed form (QR of the folded equations)";
  return fit;
}

LinearFit SolveWls(const StackedFactors& factors) {
  // Per-joint noise from the OLS residuals, with the degrees of freedom shared
  // evenly among joints.
  const LinearFit ols = SolveOls(factors);
  const double n_samples = static_cast<double>(factors.n_samples());
  const double per_joint_dof = (n_samples * factors.n_dof() - ols.rank) / factors.n_dof();
  Eigen::VectorXd sigma = (ols.joint_rms.array().square() * n_samples / per_joint_dof).sqrt();
  const double floor = 1e-12 * std::max(1.0, sigma.maxCoeff());
  sigma = sigma.cwiseMax(floor);
  LinearFit fit = Fit(factors, sigma.cwiseInverse());
  fit.joint_sigma = sigma;
  fit.solve.message = "closed form (QR), joints weighted by 1/σ_j of the OLS residual";
  return fit;
}

LinearFit SolveOls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  return SolveOls(FactorStackedRows(W, tau, n_dof));
}

LinearFit SolveWls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof) {
  return SolveWls(FactorStackedRows(W, tau, n_dof));
}

}  // namespace idbench
