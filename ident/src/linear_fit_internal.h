// Pieces of the least-squares fit (linear_estimator.cc) that the other
// estimators of the base parameters (TLS) share.
#pragma once

#include <Eigen/Core>

namespace idbench::internal {

// R D with unit columns (D = 1/‖column‖), so that units do not decide the
// rank. A column below 1e-9 of the largest is zero in R D, with D = 1.
Eigen::MatrixXd UnitColumns(const Eigen::MatrixXd& R, Eigen::VectorXd* D);

// Singular values of the column-normalised R below this × the largest count
// as zero (the data do not determine that direction).
inline constexpr double kRankTolerance = 1e-6;

}  // namespace idbench::internal
