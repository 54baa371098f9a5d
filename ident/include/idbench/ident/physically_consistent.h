// Physically consistent estimation of the standard parameters: the least-squares
// fit of the base parameters restricted to parameters that some mass
// distribution can have (Rucker & Wensing 2022, "Smooth parameterization of
// rigid-body inertia", IEEE RA-L 7(2):2771–2778).
//
// Per link, with the 10 parameters about the link frame origin Bo in the order
// of joint_torque_regressor.h, the pseudo-inertia is the second moment of the
// mass distribution about Bo,
//   J = ∫ [r; 1][r; 1]ᵀ dm = [[Σ, h], [hᵀ, m]],  Σ = ½ tr(I) 𝟙 − I,  h = m c,
// and parameters are physically consistent iff J ⪰ 0 (Wensing, Kim & Slotine
// 2017; this contains m ≥ 0, I ⪰ 0 and the triangle inequalities of I).
//
// Log-Cholesky coordinates θ = (α, d1, d2, d3, s12, s23, s13, t1, t2, t3) ∈ ℝ¹⁰
// (the paper's eq. 12, in its order) map smoothly and one-to-one onto J ≻ 0:
//   J = U Uᵀ,  U = e^α [[e^d1, s12, s13, t1],
//                       [0,    e^d2, s23, t2],
//                       [0,    0,    e^d3, t3],
//                       [0,    0,    0,    1 ]],
// so m = e^{2α}, the centre of mass is c = (t1, t2, t3), and the second moment
// about the centre of mass is m L Lᵀ with L the upper-left 3×3 block of U/e^α.
// Every θ gives a consistent body, so the constrained fit becomes an
// unconstrained smooth minimisation over θ.
#pragma once

#include <Eigen/Core>
#include <string>

#include "idbench/ident/base_parameters.h"

namespace idbench {

using InertialParameters = Eigen::Matrix<double, 10, 1>;  // [m, mcx, mcy, mcz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]
using LogCholeskyParameters = Eigen::Matrix<double, 10, 1>;  // θ = (α, d1, d2, d3, s12, s23, s13, t1, t2, t3)

// J [kg, kg m, kg m²] of one link's 10 parameters. Throws std::invalid_argument
// unless pi10 has 10 entries.
Eigen::Matrix4d PseudoInertia(const Eigen::Ref<const Eigen::VectorXd>& pi10);

// The 10 parameters of a pseudo-inertia (inverse of PseudoInertia; reads the
// symmetric part of J): m = J₃₃, h = J₀:₃,₃, I = tr(Σ) 𝟙 − Σ.
InertialParameters InertialParametersFromPseudoInertia(const Eigen::Matrix4d& J);

// The 10 parameters at θ and, if d_pi_d_theta is not null, the Jacobian
// ∂π/∂θ (10 × 10, column k = ∂π/∂θ_k).
InertialParameters InertialParametersFromLogCholesky(const Eigen::Ref<const Eigen::VectorXd>& theta,
                                                     Eigen::Matrix<double, 10, 10>* d_pi_d_theta = nullptr);

// θ of a positive definite J, from the Cholesky factor of the row- and
// column-reversed J (which gives the upper-triangular U with J = U Uᵀ).
// Throws std::invalid_argument if J is not positive definite.
LogCholeskyParameters LogCholeskyFromPseudoInertia(const Eigen::Matrix4d& J);

// Smallest eigenvalue of each link's J for the first 10·n_links entries of π
// (n_links). ≥ 0 for every link ⇔ π is physically consistent. Throws
// std::invalid_argument if π has fewer than 10·n_links entries.
Eigen::VectorXd MinPseudoInertiaEigenvalues(const Eigen::VectorXd& pi, int n_links);

// The standard parameters nearest to a prior that reproduce β exactly:
//   π = π_prior + C⁺ (β − C π_prior),  C = base.combination,
// i.e. argmin ‖π − π_prior‖ subject to C π = β. Not physically consistent in
// general. Throws std::invalid_argument on size mismatch.
Eigen::VectorXd ClosestStandardParameters(const BaseParameters& base, const Eigen::VectorXd& beta,
                                          const Eigen::VectorXd& pi_prior);

struct PhysicallyConsistentOptions {
  int max_evaluations = 2000;        // objective + gradient evaluations
  // Stop when an iteration lowers the cost by less than this fraction of it.
  double relative_tolerance = 1e-12;
  // Start: each link's J from ClosestStandardParameters gets its eigenvalues
  // raised to at least eigenvalue_floor × its largest eigenvalue.
  double eigenvalue_floor = 1e-6;

  bool IsValid(std::string* why) const;
};

struct PhysicallyConsistentFit {
  Eigen::VectorXd pi;     // standard parameters, every link physically consistent (n_standard)
  Eigen::VectorXd beta;   // base parameters C·π (n_base)
  double cost = 0.0;      // ‖W_b β − τ‖² [N² m²] of this estimate
  double ols_cost = 0.0;  // ‖W_b β_ols − τ‖² of the unconstrained estimate passed in
  double start_cost = 0.0;  // ‖W_b C π₀ − τ‖² at the consistent start π₀
  Eigen::VectorXd min_pseudo_inertia_eigenvalue;  // per link, > 0 up to rounding (n_links)
  int evaluations = 0;    // objective + gradient evaluations
  std::string status;     // NLopt's result, e.g. "FTOL_REACHED"
  bool converged = false; // NLopt stopped on a tolerance rather than a limit or failure
};

// f(x) = ‖W_b C π(x) − τ‖² and its gradient, over x = (θ_1, …, θ_n_links,
// friction): the links' log-Cholesky coordinates, then the remaining entries
// of π (friction) unchanged. With the thin QR W_b = Q₁ R, computed once,
//   f = ‖R C π − Q₁ᵀ τ‖² + ‖Q₂ᵀ τ‖²,
// so an evaluation costs O(n_base · n_standard) and not O(rows);
//   ∇f = (∂π/∂x)ᵀ 2 (R C)ᵀ (R C π − Q₁ᵀ τ), ∂π/∂x block-diagonal.
class PhysicallyConsistentObjective {
 public:
  // Throws std::invalid_argument unless W_base is rows × n_base with rows ≥
  // n_base, τ has rows entries, and the combination has ≥ 10·n_links columns.
  PhysicallyConsistentObjective(const Eigen::MatrixXd& W_base, const Eigen::VectorXd& tau,
                                const BaseParameters& base, int n_links);

  int n_variables() const { return static_cast<int>(A_.cols()); }
  int n_links() const { return n_links_; }

  // π(x) (n_standard) and its inverse (throws std::invalid_argument unless every
  // link's J is positive definite).
  Eigen::VectorXd StandardParametersAt(const Eigen::VectorXd& x) const;
  Eigen::VectorXd VariablesAt(const Eigen::VectorXd& pi) const;

  // f(x) [N² m²]; writes ∇f into *gradient (resized to n_variables) if not
  // null. Uses member workspace: not thread-safe; does not allocate once the
  // gradient is sized. Throws std::invalid_argument unless x has n_variables entries.
  double Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient = nullptr);

 private:
  int n_links_ = 0;
  Eigen::MatrixXd A_;          // R C (n_base × n_standard)
  Eigen::VectorXd b_;          // Q₁ᵀ τ (n_base)
  double residual_floor_ = 0;  // ‖Q₂ᵀ τ‖², the least cost any β reaches
  // Workspace.
  Eigen::VectorXd pi_, r_, g_pi_;
  Eigen::MatrixXd jacobians_;  // ∂π/∂θ per link, side by side (10 × 10·n_links)
};

// Minimises ‖W_b C π − τ‖² over physically consistent π (unconstrained in the
// log-Cholesky coordinates; friction entries after 10·n_links are free) with
// NLopt's L-BFGS, from the start
//   π₀ = ClosestStandardParameters(base, β_ols, π_prior), each link's J
//   projected to eigenvalues ≥ eigenvalue_floor × its largest.
// β_ols is normally SolveOls(W_b, τ, n_dof).beta. Rows may be pre-weighted
// (WLS): the cost is whatever ‖W_b β − τ‖² the rows define. Throws
// std::invalid_argument on invalid options or sizes (see the objective) or if
// β_ols, π_prior are not finite; a stop on the evaluation limit or a solver
// failure is reported in status, with the best iterate found.
PhysicallyConsistentFit SolvePhysicallyConsistent(const Eigen::MatrixXd& W_base, const Eigen::VectorXd& tau,
                                                  const BaseParameters& base, int n_links,
                                                  const Eigen::VectorXd& beta_ols, const Eigen::VectorXd& pi_prior,
                                                  const PhysicallyConsistentOptions& options = {});

}  // namespace idbench
