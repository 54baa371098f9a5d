#include "idbench/excitation/design_criterion.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace idbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRankTolerance = 1e-12;  // σ_i ≤ this × σ_max counts as zero

// Singular values of W, descending, and (if V) the right singular vectors:
// the SVD of R from W = QR when W is tall (R is p × p), of W otherwise.
Eigen::VectorXd SingularValues(const Eigen::MatrixXd& W, Eigen::MatrixXd* V = nullptr) {
  const unsigned flags = V ? static_cast<unsigned>(Eigen::ComputeFullV) : 0u;
  if (W.rows() > W.cols()) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(W);
    const Eigen::MatrixXd R = qr.matrixQR().topRows(W.cols()).triangularView<Eigen::Upper>();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, flags);
    if (V) *V = svd.matrixV();
    return svd.singularValues();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, flags);
  if (V) *V = svd.matrixV();
  return svd.singularValues();
}

// Eigen-pairs of M = WᵀW/m, ascending: λ_i = σ_i²/m. From M itself while
// λ_min/λ_max ≥ 1e-12 (i.e. cond(W) ≤ 1e6, where forming WᵀW loses at most
// 1e-4 relative in λ_min), else from the SVD.
void Spectrum(const Eigen::MatrixXd& W, Eigen::VectorXd* lambda, Eigen::MatrixXd* V) {
  const Eigen::Index p = W.cols();
  const double m = static_cast<double>(W.rows());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(p, p);
  M.selfadjointView<Eigen::Lower>().rankUpdate(W.transpose(), 1.0 / m);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
  if (eig.eigenvalues()(0) >= 1e-12 * eig.eigenvalues()(p - 1)) {
    *lambda = eig.eigenvalues();
    *V = eig.eigenvectors();
    return;
  }
  Eigen::MatrixXd V_desc;
  const Eigen::VectorXd sigma = SingularValues(W, &V_desc);
  *lambda = sigma.reverse().array().square() / m;
  *V = V_desc.rowwise().reverse();
}

// log cond(W) and its gradient (1/m) W (v_max v_maxᵀ/λ_max − v_min v_minᵀ/λ_min),
// plus (when sum_log) Σ log(σ_i/√m) = ½ Σ log λ_i and its gradient (1/m) W V Λ⁻¹ Vᵀ.
struct SpectralTerms {
  double log_cond = kInf, sum_log = -kInf;
  Eigen::MatrixXd d_log_cond, d_sum_log;
};

SpectralTerms ComputeSpectralTerms(const Eigen::MatrixXd& W, bool want_sum_log, bool want_gradient) {
  SpectralTerms terms;
  Eigen::VectorXd lambda;
  Eigen::MatrixXd V;
  Spectrum(W, &lambda, &V);
  const Eigen::Index p = W.cols();
  const double lmin = lambda(0), lmax = lambda(p - 1);
  if (!(lmax > 0.0) || !(lmin > kRankTolerance * kRankTolerance * lmax)) return terms;
  const double m = static_cast<double>(W.rows());
  terms.log_cond = 0.5 * std::log(lmax / lmin);
  if (want_sum_log) terms.sum_log = 0.5 * lambda.array().log().sum();
  if (!want_gradient) return terms;
  const Eigen::VectorXd Wv_max = W * V.col(p - 1), Wv_min = W * V.col(0);
  terms.d_log_cond = (Wv_max * V.col(p - 1).transpose() / lmax - Wv_min * V.col(0).transpose() / lmin) / m;
  if (want_sum_log) {
    terms.d_sum_log = (W * (V * lambda.cwiseInverse().asDiagonal() * V.transpose())) / m;
  }
  return terms;
}

}  // namespace

std::vector<std::string> DesignCriterionNames() { return kDesignCriterionNames.Names(); }

std::string DesignCriterionName(DesignCriterion criterion) {
  return std::string(kDesignCriterionNames.Name(criterion));
}

bool ParseDesignCriterion(std::string_view text, DesignCriterion* criterion, std::string* why) {
  return kDesignCriterionNames.Parse(text, criterion, why);
}

Identifiability ComputeIdentifiability(const Eigen::MatrixXd& W) {
  Identifiability id;
  id.rows = static_cast<int>(W.rows());
  id.cols = static_cast<int>(W.cols());
  if (W.size() == 0) return id;
  const Eigen::VectorXd sigma = SingularValues(W);
  id.sigma_max = sigma(0);
  id.sigma_min = sigma(sigma.size() - 1);
  id.rank = static_cast<int>((sigma.array() > kRankTolerance * id.sigma_max).count());
  const bool full_rank = id.rank == id.cols && W.rows() >= W.cols();
  id.cond = full_rank ? id.sigma_max / id.sigma_min : kInf;
  id.log_det = full_rank ? 2.0 * (sigma.array() / std::sqrt(double(W.rows()))).log().sum() : -kInf;
  const Eigen::VectorXd norms = W.colwise().norm();
  if (full_rank && (norms.array() > 0.0).all()) {
    const Eigen::VectorXd s = SingularValues(W * norms.cwiseInverse().asDiagonal());
    id.cond_normalised = s(0) / s(s.size() - 1);
  } else {
    id.cond_normalised = kInf;
  }
  return id;
}

double EvaluateDesignCriterion(DesignCriterion criterion, const Eigen::MatrixXd& W, Eigen::MatrixXd* dc_dW) {
  const bool gradient = dc_dW != nullptr;
  const double p = static_cast<double>(W.cols());
  if (gradient) dc_dW->setZero(W.rows(), W.cols());
  switch (criterion) {
    case DesignCriterion::kLogCond: {
      SpectralTerms t = ComputeSpectralTerms(W, false, gradient);
      if (gradient && std::isfinite(t.log_cond)) *dc_dW = std::move(t.d_log_cond);
      return t.log_cond;
    }
    case DesignCriterion::kLogCondNormalised: {
      // W̃ = W D⁻¹; for column k: ∂c/∂W_k = (G̃_k − W̃_k (W̃_kᵀ G̃_k)) / D_k.
      const Eigen::RowVectorXd norms = W.colwise().norm();
      if (!(norms.array() > 0.0).all()) return kInf;
      const Eigen::MatrixXd Wn = W * norms.cwiseInverse().asDiagonal();
      SpectralTerms t = ComputeSpectralTerms(Wn, false, gradient);
      if (gradient && std::isfinite(t.log_cond)) {
        const Eigen::MatrixXd& Gn = t.d_log_cond;
        const Eigen::RowVectorXd proj = (Wn.array() * Gn.array()).colwise().sum();
        *dc_dW = (Gn - Wn * proj.asDiagonal()) * norms.cwiseInverse().asDiagonal();
      }
      return t.log_cond;
    }
    case DesignCriterion::kLogDet: {
      SpectralTerms t = ComputeSpectralTerms(W, true, gradient);
      if (!std::isfinite(t.log_cond)) return kInf;
      if (gradient) *dc_dW = (-2.0 / p) * t.d_sum_log;
      return -2.0 / p * t.sum_log;
    }
    case DesignCriterion::kHybrid: {
      SpectralTerms t = ComputeSpectralTerms(W, true, gradient);
      if (!std::isfinite(t.log_cond)) return kInf;
      if (gradient) *dc_dW = t.d_log_cond - t.d_sum_log / p;
      return t.log_cond - t.sum_log / p;
    }
  }
  return kInf;
}

}  // namespace idbench
