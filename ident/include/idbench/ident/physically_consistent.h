// Physically consistent estimation of the standard parameters: the least-squares
// fit of the base parameters over the parameters that some mass distribution
// can have, made unconstrained by factoring each link's pseudo-inertia
// (Rucker & Wensing 2022, "Smooth parameterization of rigid-body inertia",
// IEEE RA-L 7(2):2771–2778).
//
// Per link, with the 10 parameters about the link frame origin Bo in the order
// of joint_torque_regressor.h, the pseudo-inertia is the second moment of the
// mass distribution about Bo,
//   J = ∫ [r; 1][r; 1]ᵀ dm = [[Σ, h], [hᵀ, m]],  Σ = ½ tr(I) 𝟙 − I,  h = m c,
// and the parameters are physically consistent iff J ⪰ 0 (Wensing, Kim &
// Slotine 2017; this implies m ≥ 0, I ⪰ 0 and the triangle inequalities of I).
//
// Both factorisations write J = U Uᵀ with U upper triangular, from 10 per-link
// coordinates in one order:
//   log-Cholesky (the paper's) θ = (α, d1, d2, d3, s12, s23, s13, t1, t2, t3),
//     U = e^α [[e^d1, s12, s13, t1], [0, e^d2, s23, t2], [0, 0, e^d3, t3], [0, 0, 0, 1]],
//     smooth and one-to-one onto J ≻ 0; m = e^{2α}, the centre of mass is
//     c = (t1, t2, t3), and the centroidal second moment is m L Lᵀ with L the
//     upper-left 3×3 block of U/e^α;
//   Cholesky u = (u44, u11, u22, u33, u12, u23, u13, u14, u24, u34), U_ij = u_ij,
//     polynomial and onto all J ⪰ 0 (not one-to-one: column signs).
// A least-squares optimum on the boundary (J singular; the usual case when the
// OLS estimate is inconsistent) is at finite u but at θ → ∞, where gradients
// vanish. On paper6r with an inconsistent OLS estimate the log-Cholesky search
// stalled at a 14% (no margin) to 160% (default margin) higher cost than the
// Cholesky one, and where it stalls moves with rounding (with the default
// margin: 2.6× or 10× the Cholesky cost for two factors of [W τ] that differ
// by rounding only), so the Cholesky factor is the default.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "idbench/ident/base_parameters.h"

namespace idbench {

// [m, mcx, mcy, mcz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz] of one link.
using InertialParameters = Eigen::Matrix<double, 10, 1>;
// θ or u, in the order above.
using PseudoInertiaFactor = Eigen::Matrix<double, 10, 1>;
// ∂π/∂θ or ∂π/∂u; column k is the derivative by coordinate k.
using FactorJacobian = Eigen::Matrix<double, 10, 10>;

enum class InertiaParameterization {
  kCholesky,     // u: onto J ⪰ 0
  kLogCholesky,  // θ: onto J ≻ 0 (Rucker & Wensing)
};

// J [kg, kg m, kg m²] of one link's 10 parameters. Throws std::invalid_argument
// unless pi10 has 10 entries.
Eigen::Matrix4d PseudoInertia(const Eigen::Ref<const Eigen::VectorXd>& pi10);

// The 10 parameters of a pseudo-inertia (inverse of PseudoInertia; reads the
// symmetric part of J): m = J₃₃, h = J₀:₃,₃, I = tr(Σ) 𝟙 − Σ.
InertialParameters InertialParametersFromPseudoInertia(const Eigen::Matrix4d& J);

// The 10 parameters of J = U Uᵀ at the coordinates of `parameterization` and,
// if jacobian is not null, ∂π/∂coordinates. Throws std::invalid_argument
// unless there are 10 coordinates.
InertialParameters InertialParametersFromFactor(InertiaParameterization parameterization,
                                                const Eigen::Ref<const Eigen::VectorXd>& coordinates,
                                                FactorJacobian* jacobian = nullptr);

// The coordinates of a positive definite J, from the Cholesky factor of the
// row- and column-reversed J (which gives the upper-triangular U with
// J = U Uᵀ and a positive diagonal). Throws std::invalid_argument unless J is
// positive definite.
PseudoInertiaFactor FactorFromPseudoInertia(InertiaParameterization parameterization, const Eigen::Matrix4d& J);

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
  InertiaParameterization parameterization = InertiaParameterization::kCholesky;
  int max_evaluations = 2000;        // objective + gradient evaluations, all rounds
  // Stop when an iteration, or a whole round, lowers the cost by less than
  // this fraction of it.
  double relative_tolerance = 1e-12;
  // Start: each link's J from ClosestStandardParameters gets its eigenvalues
  // raised to at least eigenvalue_floor × its largest.
  double eigenvalue_floor = 1e-6;
  // The fit keeps every link's J ⪰ margin · diag(J₀), J₀ its start: strictly
  // positive definite (m > 0, I about the centre of mass positive definite,
  // so a robot file can be written from it) at a negligible change of the
  // cost. 0 allows singular J (a rod, a plate), which the Cholesky factor
  // reaches at finite coordinates. At most eigenvalue_floor / 2.
  double pseudo_inertia_margin = 1e-7;
  // Indices into π of friction terms kept ≥ 0 (π_k = v_k², v_k free), e.g.
  // the Fv, Fc and Ia entries, which a robot file requires ≥ 0; the other
  // friction entries are free. Each must be ≥ 10·n_links.
  std::vector<int> nonnegative;

  bool IsValid(std::string* why) const;
};

// A bound of the plausible fit (plausible_fit.h) that its optimum lies on.
struct ActiveBound {
  enum class Quantity { kMass, kComX, kComY, kComZ, kTotalMass };
  Quantity quantity = Quantity::kMass;
  int link = -1;              // index; -1 for the total mass
  bool upper = false;         // the upper bound (else the lower)
  double bound = 0.0;         // [kg] or [m] (link frame B)
  double file_value = 0.0;    // the prior's (robot file's) value of the same quantity [kg] or [m]
  std::string text;           // e.g. "link 'wrist_1_link': mass at its lower bound 0.6 kg (0.5 × the file's 1.2 kg)"
};

struct PhysicallyConsistentFit {
  Eigen::VectorXd pi;     // standard parameters, every link's J ⪰ margin (n_standard)
  Eigen::VectorXd beta;   // base parameters C·π (n_base)
  double cost = 0.0;        // ‖W_b β − τ‖² [N² m²] of this estimate
  double ols_cost = 0.0;    // ‖W_b β_ols − τ‖² of the unconstrained estimate passed in
  double start_cost = 0.0;  // ‖W_b C π₀ − τ‖² at the consistent start π₀
  Eigen::VectorXd min_pseudo_inertia_eigenvalue;  // per link, > 0 with a margin (n_links)
  int evaluations = 0;    // objective + gradient evaluations
  int rounds = 0;         // NLopt runs (each re-preconditioned)
  std::string status;     // the last round's NLopt result, e.g. "FTOL_REACHED"
  bool converged = false; // stopped on a tolerance or by rounding, not on max_evaluations
  // SolvePlausibleFit (plausible_fit.h) only:
  double prior_cost = 0.0;   // the prior term λ‖x‖² at the optimum [N² m²]
  double duality_gap = std::numeric_limits<double>::quiet_NaN();  // relative, certifies the optimum
  double zero_cost = 0.0;     // ‖τ‖² [N² m²], the cost of β = 0: the scale of the data
  bool feasible = false;      // pi satisfies every constraint strictly
  std::vector<std::string> active_bounds;  // the texts of bounds_at_optimum
  std::vector<ActiveBound> bounds_at_optimum;
};

// f(x) = ‖W_b C π(x) − τ‖² and its gradient, over x = (factor of link 1, …,
// factor of link n_links, friction): each link's 10 coordinates, then the
// remaining entries of π (friction), as is or, for the nonnegative ones,
// squared (π_k = x_k²). From the triangular factor [R z; 0 ρ] of [W_b τ]
// (CombinedFactor, linear_estimator.h),
//   f = ‖r‖² + ρ²,  r = R C π(x) − z,
// so an evaluation costs O(n_base · n_standard) and not O(rows);
//   ∇f = 2 (∂π/∂x)ᵀ (R C)ᵀ r,  ∂π/∂x block-diagonal.
class PhysicallyConsistentObjective {
 public:
  // Throws std::invalid_argument unless `factor` is (n_base + 1) × (n_base + 1)
  // and finite, and the combination has ≥ 10·n_links columns.
  // Link l's pseudo-inertia is J_l = U_l U_lᵀ + margins[l] (margins empty:
  // none; else n_links symmetric matrices); `nonnegative` lists friction
  // indices into π that are squares. Also throws unless margins is empty or
  // has n_links entries and every nonnegative index is a friction entry.
  PhysicallyConsistentObjective(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                InertiaParameterization parameterization = InertiaParameterization::kCholesky,
                                const std::vector<Eigen::Matrix4d>& margins = {},
                                const std::vector<int>& nonnegative = {});

  int n_variables() const { return static_cast<int>(A_.cols()); }
  int n_links() const { return n_links_; }
  double residual_floor() const { return residual_floor_; }  // ρ² [N² m²], the least f

  // π(x) (n_standard) and an x with π(x) = π (throws std::invalid_argument
  // unless every link's J − margin is positive definite and every nonnegative
  // entry is ≥ 0).
  Eigen::VectorXd StandardParametersAt(const Eigen::VectorXd& x) const;
  Eigen::VectorXd VariablesAt(const Eigen::VectorXd& pi) const;

  // f(x) [N² m²]; writes ∇f into *gradient (resized to n_variables) if not
  // null. Uses member workspace: not thread-safe; does not allocate once the
  // gradient is sized. Throws std::invalid_argument unless x has n_variables entries.
  double Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient = nullptr);

  // r(x) (n_base) and ∂r/∂x = R C ∂π/∂x (n_base × n_variables); 2 (∂r/∂x)ᵀ ∂r/∂x
  // is the Gauss–Newton curvature of f.
  Eigen::VectorXd Residual(const Eigen::VectorXd& x) const;
  Eigen::MatrixXd ResidualJacobian(const Eigen::VectorXd& x) const;

 private:
  int n_links_ = 0;
  InertiaParameterization parameterization_;
  Eigen::MatrixXd A_;          // R C (n_base × n_standard)
  Eigen::VectorXd b_;          // z (n_base)
  double residual_floor_ = 0;  // ρ²
  Eigen::VectorXd pi_margin_;  // π of the margins, zero friction (n_standard)
  std::vector<int> squared_;   // friction indices with π_k = x_k²
  // Workspace.
  Eigen::VectorXd pi_, r_, g_pi_;
  Eigen::MatrixXd jacobians_;  // ∂π/∂x per link, side by side (10 × 10·n_links)
};

// Minimises ‖W_b C π − τ‖² over physically consistent π (every link's
// J ⪰ pseudo_inertia_margin · diag(J₀) ⪰ 0; friction entries after 10·n_links
// free, or ≥ 0 if listed in options.nonnegative) with NLopt's SLSQP on the
// unconstrained objective above, from
//   π₀ = ClosestStandardParameters(base, β_ols, π_prior), each link's J
//   projected to eigenvalues ≥ eigenvalue_floor × its largest, each
//   nonnegative entry raised to ≥ eigenvalue_floor × max(1, |π₀_k|, |π_prior_k|).
// Each round runs SLSQP in coordinates z with x = x_b + L⁻ᵀ z, L Lᵀ the
// Gauss–Newton curvature at the best point x_b so far (lightly damped), so
// that the Hessian starts near 𝟙 whatever the units; rounds repeat while one
// lowers the cost by more than relative_tolerance. Towards an optimum on the
// boundary the cost converges sublinearly: expect MAXEVAL_REACHED there (on
// the paper6r tests the default budget ends 4·10⁻⁶ and 2·10⁻⁵ above the cost
// reached with 20 000 evaluations).
// `factor` is the triangular factor [R z; 0 ρ] of [W_b τ] (CombinedFactor,
// linear_estimator.h: of a dense W_b or of streamed StackedFactors), β_ols
// normally R⁻¹ z (SolveOls). Rows may be weighted (WLS): the cost is whatever
// ‖W_b β − τ‖² the factor defines. Throws std::invalid_argument on invalid
// options or sizes (see the objective) or if β_ols, π_prior are not finite; a
// stop on max_evaluations or a solver failure is reported in
// status/converged, with the best point found.
PhysicallyConsistentFit SolvePhysicallyConsistent(const Eigen::MatrixXd& factor,
                                                  const BaseParameters& base, int n_links,
                                                  const Eigen::VectorXd& beta_ols, const Eigen::VectorXd& pi_prior,
                                                  const PhysicallyConsistentOptions& options = {});

}  // namespace idbench
