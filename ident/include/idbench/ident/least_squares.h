// Rank-revealing linear least squares that says which unknowns the data
// determine. Never forms normal equations.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace idbench {

struct LeastSquaresOptions {
  // A column whose norm is below zero_column_tolerance × reference is zero
  // (the unknown is not excited). reference <= 0 means the largest column norm.
  double zero_column_tolerance = 1e-9;
  double column_norm_reference = 0.0;
  // Singular values of the column-normalised matrix below rank_tolerance ×
  // σ_max count as zero.
  double rank_tolerance = 1e-9;
};

struct LeastSquaresSolution {
  Eigen::VectorXd x;                 // estimate; meaningful only where identifiable
  std::vector<bool> identifiable;    // per unknown
  std::vector<std::string> reason;   // why an unknown is not identifiable ("" if it is)
  int rank = 0;                      // numerical rank
  double cond = 0.0;                 // cond(A) over the identifiable columns (σ_max/σ_min); 0 if none
  double cond_normalized = 0.0;      // the same with unit-norm columns
  double residual_norm = 0.0;        // ‖A x − b‖
};

// cond(A) = σ_max/σ_min by SVD (never cond(AᵀA)); +inf if rank deficient,
// 0 for a matrix without columns.
double ConditionNumber(const Eigen::MatrixXd& A);

// Solves min ‖A x − b‖ and classifies every unknown: identifiable iff its unit
// vector lies in the row space of A, i.e. the data fix it uniquely. Unknowns
// that are not identifiable get a reason naming the zero or dependent column
// (by `names`, if given) and x = NaN. Throws std::invalid_argument if the
// sizes differ or A or b holds NaN or Inf.
LeastSquaresSolution SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                       const std::vector<std::string>& names = {},
                                       const LeastSquaresOptions& options = {});

}  // namespace idbench
