// Physical consistency of a link's inertial parameters, and the result of the
// physically consistent fit (plausible_fit.h solves it).
//
// Per link, with the 10 parameters about the link frame origin Bo in the order
// of joint_torque_regressor.h, the pseudo-inertia is the second moment of the
// mass distribution about Bo,
//   J = ∫ [r; 1][r; 1]ᵀ dm = [[Σ, h], [hᵀ, m]],  Σ = ½ tr(I) 𝟙 − I,  h = m c,
// and the parameters are physically consistent iff J ⪰ 0 (Wensing, Kim &
// Slotine 2017; this implies m ≥ 0, I ⪰ 0 and the triangle inequalities of I).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace idbench {

// [m, mcx, mcy, mcz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz] of one link.
using InertialParameters = Eigen::Matrix<double, 10, 1>;

// J [kg, kg m, kg m²] of one link's 10 parameters. Throws std::invalid_argument
// unless pi10 has 10 entries.
Eigen::Matrix4d PseudoInertia(const Eigen::Ref<const Eigen::VectorXd>& pi10);

// Smallest eigenvalue of each link's J for the first 10·n_links entries of π
// (n_links). ≥ 0 for every link ⇔ π is physically consistent. Throws
// std::invalid_argument if π has fewer than 10·n_links entries.
Eigen::VectorXd MinPseudoInertiaEigenvalues(const Eigen::VectorXd& pi, int n_links);

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
  int evaluations = 0;    // the solver's iterations (Newton steps)
  std::string status;     // how the solver stopped, in words
  bool converged = false; // the duality gap certifies the optimum
  double prior_cost = 0.0;   // the prior term λ‖x‖² at the optimum [N² m²]
  double duality_gap = std::numeric_limits<double>::quiet_NaN();  // relative, certifies the optimum
  double zero_cost = 0.0;     // ‖τ‖² [N² m²], the cost of β = 0: the scale of the data
  bool feasible = false;      // pi satisfies every constraint strictly
  std::vector<std::string> active_bounds;  // the texts of bounds_at_optimum
  std::vector<ActiveBound> bounds_at_optimum;
};

}  // namespace idbench
