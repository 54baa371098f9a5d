#include "idbench/ident/reweighted_least_squares.h"

#include <algorithm>
#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

namespace idbench {

namespace {
// A relative change of the scales between passes within the median's
// resolution (a few of the histogram's bins, robust_weights.h).
constexpr double kScaleSettled = 0.01;
constexpr double kScaleShrink = 10.0;
// MAD / 0.6745: the standard deviation of Gaussian noise from the median of |r|.
constexpr double kMadToSigma = 1.0 / 0.6744897501960817;

// Per-joint scales kept at or above 10⁻⁹ of the joint's RMS torque (a
// noise-free log: its residual is rounding, whose scale says nothing and
// changes from pass to pass), at or above kJointScaleRange⁻¹ of the largest
// joint's (the weights 1/s_j² of the joints within kJointScaleRange² of each
// other: a joint fitted to rounding would otherwise outweigh the others by
// 10²⁰ and take the columns only they excite out of the rank), and above 10⁻³⁰⁰.
constexpr double kJointScaleRange = 1e3;
Eigen::VectorXd FlooredScales(const Eigen::VectorXd& scale, const Eigen::VectorXd& tau_rms) {
  const Eigen::VectorXd floored = scale.cwiseMax(1e-9 * tau_rms).cwiseMax(1e-300);
  return floored.cwiseMax(floored.maxCoeff() / kJointScaleRange);
}
// σ of the M-estimator (Huber 1981, §7.6): G Ω₀ G with the bread
// G = (Σ ψ'/s² x xᵀ)⁻¹ where the weights' (Σ w x xᵀ)⁻¹ would be too small (for
// Huber by E[ψ']/E[ψ/u], 0.85 on Gaussian noise), and Ω₀ = Σ (w r)² x xᵀ of
// independent rows (the batch-means pass replaces it). Kept as the weighted
// fit's when W is rank deficient or the Hessian is not positive definite
// (Tukey far from its solution).
void SetSandwich(const IrlsPassRecord& pass, LinearFit* fit) {
  const Eigen::Index p = fit->beta.size();
  if (fit->rank < p) return;
  const Eigen::LDLT<Eigen::MatrixXd> hessian(pass.Hessian());
  if (hessian.info() != Eigen::Success || !(hessian.vectorD().array() > 0.0).all()) return;
  fit->gram_inverse = hessian.solve(Eigen::MatrixXd::Identity(p, p));
  fit->covariance = fit->gram_inverse * pass.WhiteScoreCovariance() * fit->gram_inverse;
  fit->covariance = 0.5 * (fit->covariance + fit->covariance.transpose()).eval();
  fit->sigma = fit->covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  fit->sigma_white = fit->sigma;
  fit->rel_sigma_percent = 100.0 * fit->sigma.cwiseQuotient(fit->beta.cwiseAbs());
}

}  // namespace

bool IrlsOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!(tuning >= 0.0) || !std::isfinite(tuning)) return fail("irls.tuning: expected >= 0 (0: the default), got " + std::to_string(tuning));
  if (max_iterations < 1 || max_iterations > 1000)
    return fail("irls.max_iterations: expected 1 to 1000, got " + std::to_string(max_iterations));
  if (!(tolerance > 0.0 && tolerance <= 0.1)) return fail("irls.tolerance: expected in (0, 0.1], got " + std::to_string(tolerance));
  return true;
}

LinearFit SolveIrls(const StackedFactors& factors, const ReweightedFold& fold, const IrlsOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const LinearFit ols = SolveOls(factors);
  const int p = factors.n_parameters;
  const double root_n = std::sqrt(static_cast<double>(factors.n_samples()));
  const Eigen::MatrixXd T = CombinedFactor(factors, Eigen::VectorXd::Ones(factors.n_dof()));
  const Eigen::MatrixXd R = T.topLeftCorner(p, p).triangularView<Eigen::Upper>();

  auto weights = std::make_shared<RobustRowWeights>();
  weights->loss = options.loss;
  weights->tuning = options.tuning > 0.0 ? options.tuning : DefaultTuning(options.loss);
  weights->beta = ols.beta;
  const Eigen::VectorXd tau_rms = JointResidualNorms(factors, Eigen::VectorXd::Zero(p)) / root_n;
  weights->scale = FlooredScales(ols.joint_rms, tau_rms);  // the first pass: OLS's RMS
  LinearFit fit;
  bool converged = false;
  bool scale_held = false;
  int k = 0;
  while (k < options.max_iterations && !converged) {
    ++k;
    // The pass: rows weighted at β_{k−1}; their residuals' median gives s_k.
    IrlsPassRecord residuals(JointResidualNorms(factors, weights->beta) / root_n, p, /*sums=*/false);
    const StackedFactors weighted = fold(*weights, &residuals);
    fit = SolveOls(weighted);
    fit.row_reweighting = weights;
    // At most kScaleShrink smaller than the last pass's: from OLS's RMS the
    // scale comes down to the MAD over a few passes, so the weights never
    // jump to 1/|r| of rows that OLS fits badly (a log whose inliers fit to
    // rounding would otherwise start as an ill-conditioned L1 fit).
    const Eigen::VectorXd scale =
        FlooredScales(kMadToSigma * residuals.Median(), tau_rms).cwiseMax(weights->scale / kScaleShrink);
    const double moved = (R * (fit.beta - weights->beta)).norm();
    const double scale_moved = ((scale - weights->scale).cwiseAbs().array() / scale.array()).maxCoeff();
    // The histogram's median moves in steps of its bins when a residual
    // crosses an edge: once the scale moves by less than kScaleSettled it is
    // held, and the passes go on with the weights' scale fixed.
    if (!scale_held && scale_moved <= kScaleSettled) scale_held = true;
    converged = moved <= options.tolerance * (R * fit.beta).norm() &&
                (scale_held || scale_moved <= 100.0 * options.tolerance);
    if (!converged && k < options.max_iterations) {
      auto next = std::make_shared<RobustRowWeights>(*weights);
      next->beta = fit.beta;
      if (!scale_held) next->scale = scale;
      weights = next;
    }
  }
  // The sandwich of the last pass: its rows again, now with their sums
  // (one more pass instead of the sums on every one).
  IrlsPassRecord last(JointResidualNorms(factors, weights->beta) / root_n, p);
  fold(*weights, &last);
  SetSandwich(last, &fit);
  // The fit of the last pass, with the unweighted residual's RMS.
  fit.joint_rms = JointResidualNorms(factors, fit.beta) / root_n;
  fit.joint_sigma = weights->scale;
  fit.solve.iterations = k;
  fit.solve.converged = converged;
  char text[300];
  std::snprintf(text, sizeof(text), "%s weights (c = %.4g) on the residual over its MAD scale: %s after %d pass%s",
                std::string(kRobustLossNames.Name(options.loss)).c_str(), weights->tuning,
                converged ? "converged" : "not converged (the iteration limit)", k, k == 1 ? "" : "es");
  fit.solve.message = text;
  return fit;
}

LinearFit SolveIrls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof, const IrlsOptions& options) {
  return SolveIrls(FactorStackedRows(W, tau, n_dof),
                   [&](const RobustRowWeights& weights, IrlsPassRecord* residuals) {
                     return FactorStackedRows(W, tau, n_dof, &weights, residuals);
                   },
                   options);
}

}  // namespace idbench
