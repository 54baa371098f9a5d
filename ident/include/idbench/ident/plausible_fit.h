// The physically consistent and plausible estimate of the standard
// parameters, solved as the convex problem it is: least squares under a 4 × 4
// linear matrix inequality per link and linear bounds (a semidefinite
// program), to a certified optimum.
//
// Over π (n_standard), with x = D⁻¹(π − π_prior) the deviation from the robot
// file in units of each parameter's scale D (PlausibleFitOptions::scale):
//   minimise  ‖W_b C π − τ‖² + λ ‖x‖²,   λ = γ ρ² / n_standard,
//   subject to  J_l(π) ⪰ ε diag(D_I, D_I, D_I, D_m)          per link l,
//               m_min,l ≤ m_l ≤ m_max,l,  M_min ≤ Σ m_l ≤ M_max
//                 (a pair of bounds closer than 10⁻⁶ of their value, a
//                 fixed mass, is held to that width: the barrier method
//                 needs an interior),
//               m_l c_min,l ≤ h_l ≤ m_l c_max,l  (centre of mass in a box),
//               π_k ≥ 0 for the listed friction terms,
// with J_l the pseudo-inertia (physically_consistent.h), h_l = m_l c_l its
// first moment, ρ² = the OLS residual (the least ‖W_b β − τ‖²). The prior term
// decides the directions the data do not determine (they stay at the robot
// file's values, projected onto the constraints) and costs γ ρ² when every
// parameter is one scale away from the file: with γ ≪ 1 it hardly moves the
// determined directions (Lee & Wensing 2020 use an entropic distance to the
// prior for the same purpose; a scaled Euclidean one keeps the objective a
// least squares). Where the data are 10⁵ times stronger than λ (nearly
// noise-free logs) λ is raised per parameter to 10⁻¹⁰ of the data's
// curvature, what double precision resolves; a direction neither the data
// nor the prior reach (γ = 0, a parameter the log does not excite) is held at
// the file's value by the weight 10⁻¹⁰ of the strongest data column.
// The data and prior rows are compressed by QR to n_standard rows and the
// program is solved by the barrier method of ident/src/quadratic_sdp.h, whose
// dual function certifies the optimum (the relative duality gap reported).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "idbench/ident/base_parameters.h"
#include "idbench/ident/physically_consistent.h"

namespace idbench {

// Bounds on one link's mass and centre of mass.
struct LinkPlausibilityBounds {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double mass_min = 0.0;    // [kg]
  double mass_max = kInf;   // [kg]
  bool bound_com = false;   // keep the centre of mass in [com_min_B, com_max_B]
  Eigen::Vector3d com_min_B = Eigen::Vector3d::Zero();  // [m], link frame B
  Eigen::Vector3d com_max_B = Eigen::Vector3d::Zero();  // [m]
  // > 0: the robot file's own centre of mass lies this far outside the box
  // around the link's shapes [m], so the box is not used as a bound.
  double com_outside_geometry = 0.0;
};

struct PlausibleFitOptions {
  std::vector<LinkPlausibilityBounds> links;  // n_links (empty: only J ⪰ εD)
  double total_mass_min = 0.0;                              // [kg]
  double total_mass_max = LinkPlausibilityBounds::kInf;     // [kg]
  std::vector<int> nonnegative;  // indices into π (friction: ≥ 10·n_links) kept ≥ 0
  // D: each standard parameter's scale (n_standard, > 0): [kg], [kg m],
  // [kg m²] and the friction units; see the top of this file.
  Eigen::VectorXd scale;
  double prior_weight = 1e-4;           // γ ≥ 0
  double pseudo_inertia_margin = 1e-6;  // ε: J − ε diag(D) ⪰ 0 keeps m > 0 and I ≻ 0
  double gap_tolerance = 1e-9;          // relative duality gap that ends the solve
  int max_iterations = 2000;            // Newton steps
  // Names in the fit's messages (ActiveBound::text): n_links URDF link names,
  // and the joints that move them; empty: "link 1", "link 2", ….
  std::vector<std::string> link_names, joint_names;

  bool IsValid(int n_links, int n_standard, std::string* why) const;
};

// Minimises the problem above. `factor` is the triangular factor [R z; 0 ρ]
// of [W_b τ] (CombinedFactor, linear_estimator.h). Returns, in the fit:
// pi, beta = Cπ, cost = ‖W_b β − τ‖² (data only), ols_cost = ρ², start_cost =
// the cost of π_prior, prior_cost = λ‖x‖², duality_gap = DSDP's primal − dual
// objective over the optimal objective (data + prior), converged when DSDP
// classes the problem feasible and that gap is ≤ 1e-7, a status that says so
// with DSDP's own stop reason (the best point is returned either way; DSDP
// may stop on a numerical limit after the gap is already far below its
// tolerance, and the gap is what certifies the optimum), evaluations = DSDP's
// iterations, and the bounds the optimum lies on. Throws
// std::invalid_argument on sizes or invalid options.
PhysicallyConsistentFit SolvePlausibleFit(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                          const Eigen::VectorXd& pi_prior, const PlausibleFitOptions& options);

}  // namespace idbench
