// Base parameters: the identifiable linear combinations of the standard
// parameters, from the regressor stacked over random states (Gautier 1990).
// The independent columns are chosen from the last backwards (Gram–Schmidt of
// the column-normalised W: a column whose residual exceeds rank_tolerance
// joins), so friction terms stay whole and the set does not depend on
// rounding among equivalent columns. With
// W = [W_b W_d] (independent, dependent columns) and W_d = W_b K, every torque
// is W π = W_b β with β = π_b + K π_d.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

struct BaseParameterOptions {
  int n_samples = 100;          // random states stacked
  unsigned seed = 1;            // explicit: results are reproducible
  double q_range = 3.14159;     // q uniform in ±q_range [rad]
  double qd_range = 3.0;        // [rad/s]
  double qdd_range = 10.0;      // [rad/s²]
  double rank_tolerance = 1e-9; // residual of a normalised column below which it is dependent
};

struct BaseParameters {
  std::vector<int> independent;       // standard indices of β's leading terms, ascending
  Eigen::MatrixXd combination;        // n_base × n_standard: β = combination · π
  std::vector<std::string> names;     // per base parameter, e.g. "B2.Izz + 0.1855 B3.m"
  std::vector<int> unexcited;         // standard indices with zero columns (no effect on τ)

  int n_base() const { return static_cast<int>(independent.size()); }
  // Base regressor from a standard one: the independent columns.
  Eigen::MatrixXd Reduce(const Eigen::MatrixXd& Y) const;
};

BaseParameters ComputeBaseParameters(const RobotModel& model, const FrictionModel& friction,
                                     const BaseParameterOptions& options = {});

}  // namespace idbench
