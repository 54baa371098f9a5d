// The plausible fit (plausible_fit.h) as the convex program the solver takes:
// shared by SolvePlausibleFit and the test that solves the same program with
// a second solver (DSDP). Internal to ident.
#pragma once

#include <Eigen/Core>

#include "idbench/ident/base_parameters.h"
#include "idbench/ident/plausible_fit.h"
#include "quadratic_sdp.h"

namespace idbench::internal {

struct PlausibleProgram {
  QuadraticSdp sdp;               // in u: π = π_prior + D ∘ u
  Eigen::VectorXd D;              // (n_standard)
  Eigen::VectorXd column_norms;   // u = x ∘ column_norms, x = options.scale⁻¹ ∘ (π − π_prior)
  Eigen::VectorXd prior_weights;  // per x_k, in units of s²
  double s2 = 1.0;                // the cost of the prior [N² m²]: the objective's unit
  double rho2 = 0.0;              // ρ², the OLS residual [N² m²]
  double start_cost = 0.0;        // the cost of π_prior [N² m²]
  double zero_cost = 0.0;         // ‖τ‖², the cost of β = 0 [N² m²]
  double rest = 0.0;              // the part of the normalised objective no u reaches
  Eigen::VectorXd start;          // u₀: the prior, nonnegative terms raised off zero
};

// Throws std::invalid_argument as SolvePlausibleFit.
PlausibleProgram MakePlausibleProgram(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                      const Eigen::VectorXd& pi_prior, const PlausibleFitOptions& options);

}  // namespace idbench::internal
