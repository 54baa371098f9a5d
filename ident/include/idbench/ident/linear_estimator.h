// Least-squares estimators of the base parameters from stacked torques
// τ = W β + e, with parameter standard deviations (Gautier & Khalil):
//   OLS: β̂ = argmin ‖W β − τ‖, σ² = ‖r‖²/(N − p), cov = σ² (WᵀW)⁻¹;
//   WLS: rows of joint j weighted by 1/σ_j, σ_j² from joint j's OLS residuals.
// That covariance holds for a white residual; residual_covariance.h replaces
// it by one from the residual as it is (coloured, per joint), which needs a
// second pass over the rows.
// Rows are ordered sample by sample, joints within a sample (row = s·n_dof + j).
// Solved by Householder QR; normal equations are never formed.
//
// The rows need not be kept: StackedFactors compresses each joint's rows
// [W_j τ_j] into a small triangular factor, block by block (TSQR: the QR of
// [T; new rows] replaces T), and both estimators, σ and cond(W) follow from
// the factors alone.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "idbench/ident/robust_weights.h"

namespace idbench {

// How a LinearFit's covariance was computed (residual_covariance.h).
enum class CovarianceMethod {
  kWhite,       // s² (WᵀW)⁻¹: as if the residual were white and of one variance
  kBatchMeans,  // the sandwich (WᵀW)⁻¹ Ω (WᵀW)⁻¹, Ω from the scores summed over time blocks
};
// "white", "batch means".
const char* ToString(CovarianceMethod method);
// "white", "batch_means" (identified.json).
const char* ToKey(CovarianceMethod method);

struct CovarianceSummary {
  CovarianceMethod method = CovarianceMethod::kWhite;
  Eigen::Index n_samples = 0;      // time instants of the fit (n_dof equations each)
  Eigen::Index block_samples = 0;  // kBatchMeans: samples per block (the last block may be shorter)
  Eigen::Index n_blocks = 0;       // kBatchMeans: blocks
  // Effective number of independent samples: n · median over the
  // identifiable parameters of (σ_white,k / σ_k)² (n for kWhite): for a
  // constant regressor and AR(1) noise of coefficient ρ, n (1 − ρ)/(1 + ρ).
  double n_effective = 0.0;
};

// How an estimate was solved: passes over the equations, and whether the
// estimator reached its solution (the verdict the tables and identified.json
// print beside it).
struct SolveSummary {
  int iterations = 1;     // OLS, WLS, TLS: 1 (closed form); IRLS: weighted passes over the equations
  bool converged = true;  // false: β is the last iterate (IRLS) or OLS's (TLS without a solution)
  std::string message;    // one line: the method, and why it stopped
};

// A least-squares estimate. When the data do not determine every parameter
// (W rank deficient: the motion does not excite some combination), beta is
// the least-squares solution of minimum norm, the parameters with a component
// along the null space are flagged not identifiable (σ = ∞), and cond = ∞.
struct LinearFit {
  Eigen::VectorXd beta;            // estimate (p); unique only where identifiable
  Eigen::MatrixXd covariance;      // (p × p); rank deficient: of the minimum-norm estimator
  Eigen::VectorXd sigma;           // standard deviations (p); ∞ where not identifiable
  // σ of the white-residual formula s² (W̃ᵀW̃)⁻¹ (p), whatever `covariance` is.
  Eigen::VectorXd sigma_white;
  CovarianceSummary covariance_method;  // how `covariance` and `sigma` were computed
  // (W̃ᵀW̃)⁻¹ of the weighted rows W̃ (p × p; rank deficient: the g-inverse of
  // the minimum-norm estimator), so that β̂ = (W̃ᵀW̃)⁻¹ W̃ᵀ τ̃: the sandwich's bread.
  Eigen::MatrixXd gram_inverse;
  Eigen::VectorXd row_weights;     // weight of joint j's rows (n_dof): 1 (OLS), 1/σ_j (WLS)
  Eigen::VectorXd rel_sigma_percent;  // 100 σ/|β| (p)
  // (WᵀW)⁻¹_kk ‖W_k‖² ≥ 1 (p): how much the other columns inflate σ_k² over
  // what column k alone would give; 1/sin² of the angle between column k and
  // the others' span. Large: the motion confuses parameter k with others.
  Eigen::VectorXd variance_inflation;
  Eigen::VectorXd joint_rms;       // residual RMS per joint [N m] (n_dof), unweighted
  Eigen::VectorXd joint_sigma;     // per-joint noise estimates (WLS weights are 1/σ_j)
  double cond = 0.0;               // cond(W) (weighted for WLS); ∞ when rank deficient
  // Numerical rank of W: of its column-normalised R, singular values above
  // 1e-6 of the largest, columns below 1e-9 of the largest counted as zero.
  int rank = 0;
  std::vector<bool> identifiable;  // per parameter: the data determine it (p)
  SolveSummary solve;
  // Scores that are not Σ_j w_j² W_tjᵀ e_tj (residual_covariance.h):
  // TLS adds this to every sample's score, so that they sum to 0 at β̂ as its
  // estimating equation says (p; empty: nothing added).
  Eigen::VectorXd score_offset;
  // IRLS: each row's own weight (RobustRowWeights::Weight at its β) in place
  // of row_weights[j]²; null: the per-joint weights.
  std::shared_ptr<const RobustRowWeights> row_reweighting;
};

// The weight of one row of joint j in a fit's scores, given its residual at
// fit.row_reweighting->beta (used only with row_reweighting): the row's own
// weight, or row_weights[j]².
inline double ScoreRowWeight(const LinearFit& fit, int joint, double residual_at_reweighting_beta) {
  if (fit.row_reweighting) return fit.row_reweighting->Weight(joint, residual_at_reweighting_beta);
  return fit.row_weights[joint] * fit.row_weights[joint];
}

// What the data say about one parameter, from its estimate β̂ and σ:
//   kDetermined: σ ≤ 10 % of |β̂|;
//   kPoor: 10 % < σ/|β̂| < 1/3;
//   kIndistinguishableFromZero: |β̂| ≤ 3σ, the data cannot tell it from 0
//   (a parameter that is 0, e.g. by symmetry, or one the motion hardly
//   excites: σ and variance_inflation tell which);
//   kNotIdentifiable: σ or β̂ not finite (LinearFit: the data do not
//   determine it).
enum class ParameterStatus { kDetermined, kPoor, kIndistinguishableFromZero, kNotIdentifiable };
inline constexpr double kDeterminedSigmaPercent = 10.0;
inline constexpr double kZeroSigmas = 3.0;
ParameterStatus ClassifyParameter(double beta, double sigma);
// "determined", "poor", "indistinguishable from zero", "not identifiable".
const char* ToString(ParameterStatus status);

// One joint's rows [W_j τ_j] (m × (p + 1)), compressed: with c the columns of
// W_j that may be non-zero (`columns`, ascending; the others must be zero in
// every row), T ((c + 1) × (c + 1), upper triangular) is the R factor of the
// rows restricted to those columns, τ last. For every β,
//   ‖W_j β − τ_j‖ = ‖T [β_columns; −1]‖.
struct JointRowFactor {
  std::vector<int> columns;  // indices into β (c)
  Eigen::MatrixXd T;         // ((c + 1) × (c + 1))
  Eigen::Index n_rows = 0;   // rows folded in (m)
};

// All joints' rows of stacked equations, compressed per joint.
struct StackedFactors {
  int n_parameters = 0;                // p
  std::vector<JointRowFactor> joints;  // n_dof

  // Empty factors (n_rows 0, T = 0) for these column sets; throws
  // std::invalid_argument unless every index lies in [0, n_parameters) and
  // each set is strictly ascending.
  StackedFactors(int n_parameters, const std::vector<std::vector<int>>& columns_per_joint);
  StackedFactors() = default;

  int n_dof() const { return static_cast<int>(joints.size()); }
  Eigen::Index n_samples() const { return joints.empty() ? 0 : joints.front().n_rows; }
};

// Folds rows of one joint into its factor: `rows` (m × (c + 1)) holds the
// joint's new rows restricted to factor->columns, τ last; it is overwritten
// (scratch). Householder reflections on [T; rows], no allocation.
void FoldJointRows(Eigen::Ref<Eigen::MatrixXd> rows, JointRowFactor* factor);

// Folds `other`'s rows into *into, joint by joint (as if its rows had been
// appended). Throws std::invalid_argument unless the column sets agree.
void MergeStackedFactors(const StackedFactors& other, StackedFactors* into);

// The factors of stacked (W, τ) (rows interleaved by joint), each joint
// restricted to the columns that are non-zero in its rows. Throws
// std::invalid_argument on size mismatch.
// With `weights`, each row is scaled by √w (RobustRowWeights::Weight) and
// its residual at weights->beta added to *residuals (if given): a pass of IRLS.
StackedFactors FactorStackedRows(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof,
                                 const RobustRowWeights* weights = nullptr, IrlsPassRecord* residuals = nullptr);

// RMS per joint of stacked residuals r (rows interleaved by joint) (n_dof).
Eigen::VectorXd JointRms(const Eigen::VectorXd& r, int n_dof);

// ‖W_j β − τ_j‖ of each joint from its factor (n_dof); at β = 0, ‖τ_j‖.
// Throws std::invalid_argument unless β has n_parameters entries.
Eigen::VectorXd JointResidualNorms(const StackedFactors& factors, const Eigen::VectorXd& beta);

// All rows in one factor: the (p + 1) × (p + 1) upper-triangular [R z; 0 ρ]
// of [W τ], joint j's rows weighted by weights[j] (n_dof), so that for every β
//   Σ_j weights[j]² ‖W_j β − τ_j‖² = ‖R β − z‖² + ρ².
// Throws std::invalid_argument unless weights has n_dof entries.
Eigen::MatrixXd CombinedFactor(const StackedFactors& factors, const Eigen::VectorXd& weights);
// The same of a dense [W τ] (unweighted). Throws std::invalid_argument on a
// size mismatch or fewer rows than columns + 1.
Eigen::MatrixXd CombinedFactor(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau);

// Throws std::invalid_argument on size mismatch or fewer rows than p + 1.
LinearFit SolveOls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof);
LinearFit SolveWls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof);

// The same from the factors (what the dense versions compute). Throws
// std::invalid_argument unless there are more equations (n_samples · n_dof)
// than parameters.
LinearFit SolveOls(const StackedFactors& factors);
LinearFit SolveWls(const StackedFactors& factors);

}  // namespace idbench
