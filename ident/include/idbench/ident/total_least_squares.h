// Total least squares (Golub & Van Loan 1980; Van Huffel & Vandewalle 1991)
// of stacked torque equations τ ≈ W β when the regressor W is noisy too (it
// is built from measured q and from qd, qdd estimated from them): β
// minimises the smallest change ‖[ΔW Δτ]‖_F that makes the equations exact.
//
// The columns are scaled first, as TLS is not invariant to their units:
// each column of W and τ to unit norm (D = diag(1/‖W_k‖), d_τ = 1/‖τ‖), so
// that the errors are taken alike in every scaled column. With v the right
// singular vector of the smallest singular value s of [W D  τ d_τ],
//   β = −D v_{1:p} / (v_{p+1} d_τ),
// equivalently (WᵀW − s² D⁻²) β = Wᵀτ: least squares with s² D⁻² taken off
// the Gram matrix, the regressor's noise it estimates. The folded
// equations suffice: [W τ] = Q T with T = [R z; 0 ρ] (CombinedFactor), and
// [W τ] diag(D, d_τ) = Q T diag(D, d_τ) has the same right singular
// vectors and values as T diag(D, d_τ), (p + 1) × (p + 1) — so a streamed
// log's factors give TLS with no second pass.
//
// When W is rank deficient (the motion does not excite every base
// parameter), TLS is taken in the directions OLS resolves (β = D V_r γ, V_r
// of the column-scaled R's SVD as in SolveOls) and the others are flagged
// not identifiable as in OLS.
//
// σ: the linearised estimating equation Σ_t [W_tᵀ(τ_t − W_t β) + s² D⁻² β/n] = 0
// with s² held fixed gives the sandwich G Ω G with G = (WᵀW − s² D⁻²)⁻¹ as
// its bread; the scores are made to sum to 0 at β̂ by score_offset, so the
// batch-means Ω of residual_covariance.h applies unchanged (and covariance
// here is its white-residual form, s_e² G WᵀW G). The noise of s² itself is
// not counted: the Monte Carlo test (tests/ident/total_least_squares_test.cc)
// checks σ against the spread of the estimates.
#pragma once

#include "idbench/ident/linear_estimator.h"

namespace idbench {

// TLS from the folded equations; the fit's solve summary says whether a TLS
// solution exists (v_{p+1} ≠ 0: otherwise β is OLS's, converged false).
// Throws std::invalid_argument as SolveOls.
LinearFit SolveTls(const StackedFactors& factors);

// The same of dense stacked rows (rows interleaved by joint).
LinearFit SolveTls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof);

}  // namespace idbench
