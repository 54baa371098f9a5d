// Iteratively reweighted least squares (IRLS) of stacked torque equations:
// an M-estimator (robust_weights.h) that gross outliers (a torque spike, a
// dropped sample, a collision) cannot pull far, where one outlier can move
// OLS anywhere. Each iteration is a weighted least-squares fit whose row
// weights come from the previous iterate's residuals (Holland & Welsch 1977):
//   pass k: w_i = Weight(r_i(β_{k−1}); s_{k−1}),  β_k = argmin Σ_i w_i (τ_i − W_i β)²,
// starting from OLS with its per-joint RMS as the scale. The weights of a
// row need the row, so each iteration is a pass over the equations (a
// streamed log is read again: `ReweightedFold`), whose memory stays that of
// the fold. The scale s_k is the MAD of the residuals that pass saw (at
// β_{k−1}), but at most 10 times smaller than s_{k−1}, so that the scale
// comes down from OLS's RMS gradually; at convergence β and s are both those
// of the fixed point.
//
// The scales are held once they move by less than 1 % between passes (the
// histogram's median moves in steps of its bins, so it would not settle
// further); the weights are then a fixed function of the residual, and the
// passes go on until the prediction moves by at most `tolerance`,
// ‖R (β_k − β_{k−1})‖ ≤ tolerance ‖R β_k‖ (R of the unweighted W: unit
// free); or stop after max_iterations passes (converged false: β is the
// last iterate).
//
// σ: the M-estimator's sandwich G Ω G (Huber 1981, §7.6) from the final
// pass, G = (Σ_i ψ'(u_i)/s_j² W_iᵀW_i)⁻¹ (not the weights' (Σ w_i W_iᵀW_i)⁻¹,
// which is too small by E[ψ']/E[ψ(u)/u], 0.85 for Huber on Gaussian noise),
// Ω = Σ_i (w_i r_i)² W_iᵀW_i of independent rows; the scores
// s_t = Σ_j w_tj W_tjᵀ e_tj (the fit's row_reweighting) let
// residual_covariance.h replace Ω by its batch means in a further pass.
// Where W is rank deficient, the weighted fit's σ.
#pragma once

#include <functional>
#include <string>

#include "idbench/ident/linear_estimator.h"
#include "idbench/ident/robust_weights.h"

namespace idbench {

struct IrlsOptions {
  RobustLoss loss = RobustLoss::kHuber;
  double tuning = 0.0;       // c; 0: DefaultTuning(loss)
  int max_iterations = 50;   // passes over the equations, in [1, 1000]
  double tolerance = 1e-8;   // relative change of the prediction W β between passes, in (0, 0.1]

  bool IsValid(std::string* why) const;
};

// One IRLS pass: the equations' rows, each scaled by √w
// (weights.Weight(joint, r) at its residual r = τ − W weights.beta), folded
// as the unweighted factors were, every residual added to *residuals.
using ReweightedFold = std::function<StackedFactors(const RobustRowWeights& weights, IrlsPassRecord* residuals)>;

// IRLS from the unweighted factors (OLS, the start) and a pass over the
// equations. The fit's joint_rms is of the unweighted residual, joint_sigma
// the robust scales s_j, row_reweighting the final weights, solve the
// passes and the verdict. Throws std::invalid_argument for invalid options
// and as SolveOls.
LinearFit SolveIrls(const StackedFactors& factors, const ReweightedFold& fold, const IrlsOptions& options = {});

// The same of dense stacked rows (rows interleaved by joint).
LinearFit SolveIrls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof,
                    const IrlsOptions& options = {});

}  // namespace idbench
