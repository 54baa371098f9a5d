// Identifiability of a regressor W (m rows × p parameter columns), and the
// criteria the excitation design minimises.
//
// Everything is stated in the singular values σ_i of W itself, never of WᵀW:
// cond(W) = σ_max/σ_min (cond(WᵀW) would be its square). The log-determinant
// is per sample, log det(WᵀW/m) = 2 Σ log(σ_i/√m), so it does not grow with
// the number of samples. "Normalised" means W with unit-norm columns, which
// removes the parameters' units from the condition number.
//
// Criteria (all minimised; natural logarithms):
//   cond             log cond(W)                                  (default)
//   cond-normalised  log cond(W D⁻¹), D = diag(‖W_k‖)
//   logdet           −(1/p) log det(WᵀW/m)       (D-optimal, per parameter)
//   hybrid           log cond(W) − (1/p) Σ log(σ_i/√m): well conditioned
//                    and large signal (σ in torque per unit parameter)
//
// Sequential design (design --given): with the information of motions
// already recorded, every criterion is that of the union, the rows of the
// given motions stacked on W. Only their Gram matrix WgᵀWg enters (every
// criterion is a function of the union's WᵀW = WgᵀWg + WᵀW and its row
// count m), so the given rows are held as a p × p triangular factor R with
// RᵀR = WgᵀWg: cond, the column norms and the singular values of [R; W] are
// those of [Wg; W].
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "idbench/engine/enum_names.h"

namespace idbench {

enum class DesignCriterion { kLogCond, kLogCondNormalised, kLogDet, kHybrid };

inline constexpr EnumNames<DesignCriterion, 4> kDesignCriterionNames{
    "criterion", {"cond", "cond-normalised", "logdet", "hybrid"}};

std::vector<std::string> DesignCriterionNames();  // "cond", "cond-normalised", "logdet", "hybrid"
std::string DesignCriterionName(DesignCriterion criterion);
// false with *why = "criterion: expected cond, cond-normalised, logdet or hybrid, got '...'".
bool ParseDesignCriterion(std::string_view text, DesignCriterion* criterion, std::string* why = nullptr);

// The information of the given motions (see above): R (p × p, upper
// triangular, RᵀR the given rows' Gram matrix, each row weighted as the
// caller chose: design weighs a second of a given log as a second of the new
// motion, GivenInformationFromFactors) and the row count those rows stand
// for (Σ weighted rows), the m of the union's log det(WᵀW/m). Empty: none.
struct GivenInformation {
  Eigen::MatrixXd R;                 // (p × p); empty: no given motion
  double n_rows = 0.0;               // rows R stands for (weighted)
  // The noise variance s² of one weighted row, from the given logs' residual
  // (σ of a parameter = s √((WᵀW)⁻¹)_kk); NaN when no given motion had
  // measured torques (a designed trajectory): σ is then per unit s.
  double noise_variance = std::numeric_limits<double>::quiet_NaN();
  bool empty() const { return R.size() == 0; }
  // Every row's weight times c: R·√c, n_rows·c, and noise_variance·c (the
  // weighted residual scales with c), so σ of the given alone is unchanged.
  GivenInformation Scaled(double c) const {
    GivenInformation out = *this;
    out.R *= std::sqrt(c);
    out.n_rows *= c;
    out.noise_variance *= c;
    return out;
  }
};

// The given information of several motions, each as its combined factor
// [R_i z_i; 0 ρ_i] ((p + 1) × (p + 1), CombinedFactor of its equations; z, ρ
// zero for a motion without torques, measured false), weighted by w_i (each
// row's weight) and counted in m_i rows: R from the QR of the stacked
// √w_i [R_i z_i; 0 ρ_i], n_rows = Σ w_i m_i, and s² = ρ²/(Σ m_i − p) of the
// weighted least-squares fit to the measured ones (ρ² = Σ w_i ‖e_i‖²: a row
// of weight w_i has noise variance s²/w_i, the same per second when w_i is
// the ratio of rates). Throws std::invalid_argument on mismatched sizes, a
// weight not > 0, or no motion.
GivenInformation GivenInformationFromFactors(const std::vector<Eigen::MatrixXd>& combined_factors,
                                             const std::vector<double>& weights,
                                             const std::vector<double>& n_rows, const std::vector<bool>& measured);

// σ of each parameter predicted from an information factor: s √((RᵀR)⁻¹)_kk
// for R = the given factor alone (W empty) or the QR of [R; W] (the union),
// s² = given.noise_variance (1 when NaN). +inf for a parameter in a
// direction the information does not determine (singular value ≤ 1e-12 of
// the largest). Throws std::invalid_argument when W's columns differ from R's.
Eigen::VectorXd PredictedSigma(const GivenInformation& given, const Eigen::MatrixXd& W = {});

struct Identifiability {
  int rows = 0, cols = 0;
  int rank = 0;                 // numerical rank (σ_i > 1e-12 σ_max)
  double sigma_max = 0.0;       // of W
  double sigma_min = 0.0;       // of W
  double cond = 0.0;            // σ_max/σ_min of W; +inf when rank deficient
  double cond_normalised = 0.0; // the same for unit-norm columns
  double log_det = 0.0;         // log det(WᵀW/m); −inf when rank deficient
};

// By SVD (QR first for tall W): the numbers every report shows. With given
// information: those of the union (rows: given.n_rows + W's, rounded).
Identifiability ComputeIdentifiability(const Eigen::MatrixXd& W, const GivenInformation& given = {});

// The criterion's value at W and, when dc_dW is given, its gradient with
// respect to every entry of W (m × p), from dσ_i = u_iᵀ dW v_i. Uses the
// eigen-decomposition of WᵀW while that is accurate (cond(W) < 1e6) and an
// SVD otherwise. A rank-deficient W gives +inf and a zero gradient.
// With given information (non-empty): the criterion of the union, and its
// gradient with respect to W's entries.
double EvaluateDesignCriterion(DesignCriterion criterion, const Eigen::MatrixXd& W,
                               Eigen::MatrixXd* dc_dW = nullptr, const GivenInformation& given = {});

}  // namespace idbench
