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
#pragma once

#include <Eigen/Core>
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

struct Identifiability {
  int rows = 0, cols = 0;
  int rank = 0;                 // numerical rank (σ_i > 1e-12 σ_max)
  double sigma_max = 0.0;       // of W
  double sigma_min = 0.0;       // of W
  double cond = 0.0;            // σ_max/σ_min of W; +inf when rank deficient
  double cond_normalised = 0.0; // the same for unit-norm columns
  double log_det = 0.0;         // log det(WᵀW/m); −inf when rank deficient
};

// By SVD (QR first for tall W): the numbers every report shows.
Identifiability ComputeIdentifiability(const Eigen::MatrixXd& W);

// The criterion's value at W and, when dc_dW is given, its gradient with
// respect to every entry of W (m × p), from dσ_i = u_iᵀ dW v_i. Uses the
// eigen-decomposition of WᵀW while that is accurate (cond(W) < 1e6) and an
// SVD otherwise. A rank-deficient W gives +inf and a zero gradient.
double EvaluateDesignCriterion(DesignCriterion criterion, const Eigen::MatrixXd& W,
                               Eigen::MatrixXd* dc_dW = nullptr);

}  // namespace idbench
