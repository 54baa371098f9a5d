#include "idbench/excitation/design_criterion.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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
// m: the rows W stands for (its own, or with given information the union's).
void Spectrum(const Eigen::MatrixXd& W, double m, Eigen::VectorXd* lambda, Eigen::MatrixXd* V) {
  const Eigen::Index p = W.cols();
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

SpectralTerms ComputeSpectralTerms(const Eigen::MatrixXd& W, double m, bool want_sum_log, bool want_gradient) {
  SpectralTerms terms;
  Eigen::VectorXd lambda;
  Eigen::MatrixXd V;
  Spectrum(W, m, &lambda, &V);
  const Eigen::Index p = W.cols();
  const double lmin = lambda(0), lmax = lambda(p - 1);
  if (!(lmax > 0.0) || !(lmin > kRankTolerance * kRankTolerance * lmax)) return terms;
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

// [R; W]: the given factor's rows on W's (W itself without given information).
Eigen::MatrixXd Union(const Eigen::MatrixXd& W, const GivenInformation& given) {
  if (given.empty()) return W;
  if (given.R.cols() != W.cols() || given.R.rows() != W.cols()) {
    throw std::invalid_argument("given information: expected a factor of " + std::to_string(W.cols()) + " x " +
                                std::to_string(W.cols()) + " (the regressor's parameters), got " +
                                std::to_string(given.R.rows()) + " x " + std::to_string(given.R.cols()));
  }
  Eigen::MatrixXd U(given.R.rows() + W.rows(), W.cols());
  U << given.R, W;
  return U;
}

double UnionRows(const Eigen::MatrixXd& W, const GivenInformation& given) {
  return static_cast<double>(W.rows()) + (given.empty() ? 0.0 : given.n_rows);
}

}  // namespace

GivenInformation GivenInformationFromFactors(const std::vector<Eigen::MatrixXd>& combined_factors,
                                             const std::vector<double>& weights,
                                             const std::vector<double>& n_rows, const std::vector<bool>& measured) {
  const size_t n = combined_factors.size();
  if (n == 0 || weights.size() != n || n_rows.size() != n || measured.size() != n) {
    throw std::invalid_argument("given information: expected at least one motion and a weight, row count and "
                                "measured flag per factor, got " + std::to_string(n) + " factors, " +
                                std::to_string(weights.size()) + " weights, " + std::to_string(n_rows.size()) +
                                " row counts, " + std::to_string(measured.size()) + " flags");
  }
  const Eigen::Index p1 = combined_factors.front().rows();
  Eigen::MatrixXd stacked(static_cast<Eigen::Index>(n) * p1, p1);
  GivenInformation given;
  double measured_rows = 0.0;
  bool any_measured = false;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::MatrixXd& F = combined_factors[i];
    if (F.rows() != p1 || F.cols() != p1 || p1 < 2 || !(weights[i] > 0.0) || !std::isfinite(weights[i])) {
      throw std::invalid_argument("given information: motion " + std::to_string(i + 1) + ": expected a factor of " +
                                  std::to_string(p1) + " x " + std::to_string(p1) + " and a weight > 0, got " +
                                  std::to_string(F.rows()) + " x " + std::to_string(F.cols()) + " and " +
                                  std::to_string(weights[i]));
    }
    stacked.middleRows(static_cast<Eigen::Index>(i) * p1, p1) = std::sqrt(weights[i]) * F;
    // A motion without torques adds information but no residual.
    if (!measured[i]) stacked.block(static_cast<Eigen::Index>(i) * p1, p1 - 1, p1, 1).setZero();
    given.n_rows += weights[i] * n_rows[i];
    if (measured[i]) {
      measured_rows += n_rows[i];
      any_measured = true;
    }
  }
  // One QR of the stacked factors: [R z; 0 ρ] of all weighted rows.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(stacked);
  const Eigen::MatrixXd T = qr.matrixQR().topRows(p1).triangularView<Eigen::Upper>();
  const Eigen::Index p = p1 - 1;
  given.R = T.topLeftCorner(p, p);
  if (any_measured && measured_rows > static_cast<double>(p)) {
    // The least-squares residual min ‖R β − z‖² + ρ²: ρ² alone when R has
    // full rank; otherwise the part of z outside R's range too (the minimum
    // norm solution, R's singular values ≤ 1e-12 of the largest as zero).
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(given.R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    svd.setThreshold(kRankTolerance);
    const Eigen::VectorXd z = T.col(p).head(p);
    const double rss = (given.R * svd.solve(z) - z).squaredNorm() + T(p, p) * T(p, p);
    given.noise_variance = rss / (measured_rows - static_cast<double>(p));
  }
  return given;
}

Eigen::VectorXd PredictedSigma(const GivenInformation& given, const Eigen::MatrixXd& W) {
  if (given.empty()) throw std::invalid_argument("predicted sigma: no given information");
  const Eigen::MatrixXd U = W.size() == 0 ? given.R : Union(W, given);
  Eigen::MatrixXd V;
  const Eigen::VectorXd sigma = SingularValues(U, &V);  // descending
  const double s2 = std::isnan(given.noise_variance) ? 1.0 : given.noise_variance;
  const Eigen::Index p = U.cols();
  Eigen::VectorXd out(p);
  for (Eigen::Index k = 0; k < p; ++k) {
    // ((UᵀU)⁻¹)_kk = Σ_i V_ki²/σ_i²; a direction of σ_i ≈ 0 that parameter k
    // takes part in leaves it undetermined.
    double variance = 0.0;
    for (Eigen::Index i = 0; i < sigma.size(); ++i) {
      if (sigma(i) <= kRankTolerance * sigma(0)) {
        if (std::abs(V(k, i)) > 1e-8) variance = kInf;
        continue;
      }
      variance += V(k, i) * V(k, i) / (sigma(i) * sigma(i));
    }
    out(k) = std::sqrt(s2 * variance);
  }
  return out;
}

std::vector<std::string> DesignCriterionNames() { return kDesignCriterionNames.Names(); }

std::string DesignCriterionName(DesignCriterion criterion) {
  return std::string(kDesignCriterionNames.Name(criterion));
}

bool ParseDesignCriterion(std::string_view text, DesignCriterion* criterion, std::string* why) {
  return kDesignCriterionNames.Parse(text, criterion, why);
}

Identifiability ComputeIdentifiability(const Eigen::MatrixXd& W_new, const GivenInformation& given) {
  Eigen::MatrixXd stacked;
  if (!given.empty()) stacked = Union(W_new, given);
  const Eigen::MatrixXd& W = given.empty() ? W_new : stacked;
  const double m = UnionRows(W_new, given);
  Identifiability id;
  id.rows = static_cast<int>(std::lround(m));
  id.cols = static_cast<int>(W.cols());
  if (W.size() == 0) return id;
  const Eigen::VectorXd sigma = SingularValues(W);
  id.sigma_max = sigma(0);
  id.sigma_min = sigma(sigma.size() - 1);
  id.rank = static_cast<int>((sigma.array() > kRankTolerance * id.sigma_max).count());
  const bool full_rank = id.rank == id.cols && W.rows() >= W.cols();
  id.cond = full_rank ? id.sigma_max / id.sigma_min : kInf;
  id.log_det = full_rank ? 2.0 * (sigma.array() / std::sqrt(m)).log().sum() : -kInf;
  const Eigen::VectorXd norms = W.colwise().norm();
  if (full_rank && (norms.array() > 0.0).all()) {
    const Eigen::VectorXd s = SingularValues(W * norms.cwiseInverse().asDiagonal());
    id.cond_normalised = s(0) / s(s.size() - 1);
  } else {
    id.cond_normalised = kInf;
  }
  return id;
}

double EvaluateDesignCriterion(DesignCriterion criterion, const Eigen::MatrixXd& W_new, Eigen::MatrixXd* dc_dW_new,
                               const GivenInformation& given) {
  // With given information: the union's criterion, and of its gradient the
  // rows of W (the given rows are fixed).
  Eigen::MatrixXd stacked;
  if (!given.empty()) stacked = Union(W_new, given);
  const Eigen::MatrixXd& W = given.empty() ? W_new : stacked;
  const double m = UnionRows(W_new, given);
  Eigen::MatrixXd union_gradient;
  Eigen::MatrixXd* dc_dW = given.empty() ? dc_dW_new : dc_dW_new ? &union_gradient : nullptr;
  struct TakeRows {  // the new rows of the union's gradient, on every return
    Eigen::MatrixXd* from;
    Eigen::MatrixXd* to;
    Eigen::Index n;
    ~TakeRows() {
      if (from && to) *to = from->bottomRows(n);
    }
  } take{given.empty() ? nullptr : dc_dW, dc_dW_new, W_new.rows()};
  const bool gradient = dc_dW != nullptr;
  const double p = static_cast<double>(W.cols());
  if (gradient) dc_dW->setZero(W.rows(), W.cols());
  switch (criterion) {
    case DesignCriterion::kLogCond: {
      SpectralTerms t = ComputeSpectralTerms(W, m, false, gradient);
      if (gradient && std::isfinite(t.log_cond)) *dc_dW = std::move(t.d_log_cond);
      return t.log_cond;
    }
    case DesignCriterion::kLogCondNormalised: {
      // W̃ = W D⁻¹; for column k: ∂c/∂W_k = (G̃_k − W̃_k (W̃_kᵀ G̃_k)) / D_k.
      const Eigen::RowVectorXd norms = W.colwise().norm();
      if (!(norms.array() > 0.0).all()) return kInf;
      const Eigen::MatrixXd Wn = W * norms.cwiseInverse().asDiagonal();
      SpectralTerms t = ComputeSpectralTerms(Wn, m, false, gradient);
      if (gradient && std::isfinite(t.log_cond)) {
        const Eigen::MatrixXd& Gn = t.d_log_cond;
        const Eigen::RowVectorXd proj = (Wn.array() * Gn.array()).colwise().sum();
        *dc_dW = (Gn - Wn * proj.asDiagonal()) * norms.cwiseInverse().asDiagonal();
      }
      return t.log_cond;
    }
    case DesignCriterion::kLogDet: {
      SpectralTerms t = ComputeSpectralTerms(W, m, true, gradient);
      if (!std::isfinite(t.log_cond)) return kInf;
      if (gradient) *dc_dW = (-2.0 / p) * t.d_sum_log;
      return -2.0 / p * t.sum_log;
    }
    case DesignCriterion::kHybrid: {
      SpectralTerms t = ComputeSpectralTerms(W, m, true, gradient);
      if (!std::isfinite(t.log_cond)) return kInf;
      if (gradient) *dc_dW = t.d_log_cond - t.d_sum_log / p;
      return t.log_cond - t.sum_log / p;
    }
  }
  return kInf;
}

}  // namespace idbench
