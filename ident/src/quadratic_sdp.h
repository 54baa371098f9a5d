// Least squares under linear matrix inequalities, solved by a primal
// log-barrier interior-point method with Newton steps (Boyd & Vandenberghe,
// Convex Optimization, §11.3 and §11.6), certified by the dual function.
//
//   minimise   f(u) = ‖R u − z‖²                      (R square, invertible)
//   subject to S_j(u) = C_j + Σ_i u_i B_ij ⪰ 0          (small symmetric blocks)
//              r_k(u) = c_k + a_kᵀ u ≥ 0
//
// Why not DSDP (Debian libdsdp-dev), which the tests use as the independent
// solver: an SDP solver needs the least squares as an epigraph LMI
// [[t, rᵀ], [r, 𝟙]] ⪰ 0, whose barrier squares the data's conditioning
// near the optimum; on a nearly noise-free log (paper6r, signal/noise 10⁵)
// DSDP stopped on an indefinite Schur matrix with a relative gap of 10⁻³ to
// 10⁻², where the quadratic objective taken as it is converges to 10⁻¹².
//
// Certificate: at a barrier point u (parameter τ), Z_j = S_j⁻¹/τ ≻ 0 and
// λ_k = 1/(τ r_k) > 0 are dual feasible, so the dual function
//   g(Z, λ) = min_v f(v) − Σ tr(Z_j S_j(v)) − Σ λ_k r_k(v)
// (a quadratic in v, minimised exactly) is a lower bound on the optimum, and
// f(u) − g ≥ f(u) − f* is the gap reported; near the centre the dual point
// one Newton step further on gives a sharper one (quadratic_sdp.cc).
// Internal to ident.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace idbench::internal {

struct LmiBlock {
  Eigen::MatrixXd C;                // symmetric, dim × dim
  std::vector<int> variables;       // the u_i that appear in this block
  std::vector<Eigen::MatrixXd> B;   // B_ij (symmetric), one per listed variable
};

struct LinearInequality {
  double c = 0.0;
  std::vector<std::pair<int, double>> a;  // (variable, coefficient)
};

struct QuadraticSdp {
  Eigen::MatrixXd R;  // n × n, invertible
  Eigen::VectorXd z;  // n
  std::vector<LmiBlock> blocks;
  std::vector<LinearInequality> rows;

  int n_variables() const { return static_cast<int>(R.cols()); }
};

struct QuadraticSdpOptions {
  // Stop when (f(u) − g) ≤ relative_gap · max(f(u) + objective_offset,
  // objective_floor): the offset is what the caller adds to f (e.g. the
  // residual no u reaches), the floor the scale below which the objective
  // counts as zero (an optimum at f ≈ 0 has no relative precision).
  double relative_gap = 1e-9;
  double objective_offset = 0.0;
  double objective_floor = 0.0;
  int max_newton_steps = 2000;   // over both phases
  Eigen::VectorXd start;         // n (empty: u = 0); need not be feasible
};

struct QuadraticSdpSolution {
  Eigen::VectorXd u;
  double objective = 0.0;     // f(u)
  double lower_bound = 0.0;   // g: f* ≥ g
  double relative_gap = 0.0;  // (f(u) − g) / max(f(u) + objective_offset, objective_floor)
  int newton_steps = 0;
  bool feasible = false;      // u satisfies every constraint strictly
  bool converged = false;     // feasible and relative_gap ≤ the option's
  std::string status;         // "converged", "infeasible: …" or why it stopped
};

// Whether u satisfies every constraint strictly (S_j(u) ≻ 0, r_k(u) > 0).
bool IsStrictlyFeasible(const QuadraticSdp& problem, const Eigen::VectorXd& u);

// Throws std::invalid_argument on inconsistent sizes or indices.
QuadraticSdpSolution SolveQuadraticSdp(const QuadraticSdp& problem, const QuadraticSdpOptions& options = {});

}  // namespace idbench::internal
