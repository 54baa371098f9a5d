// The equations that the payload sub-problems share (drive_gains.h,
// payload_estimator.h): one log's stacked rows with the robot's base
// regressor, one link's 10 standard columns and the caller's own columns
// (torques, currents), filtered in parallel when the log's derivatives were
// estimated; and their minimum-norm least-squares solution with the unknowns'
// identifiability and covariance. Internal to ident.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/ident/least_squares.h"

namespace idbench::internal {

// Rows interleaved by joint (s·n + j) of
//   [W (n_base, when base is given) | Y_link (10: [m, mcx, …, Izz] of link `link`) | extra]
// at every sample of `motion` (t, q, qd, qdd); `extra` holds the caller's
// columns already stacked ((n_samples·n) × k), filtered with the rest. Throws
// std::invalid_argument (prefixed by `which`) when motion or extra do not fit
// the robot.
Eigen::MatrixXd StackLinkEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters* base,
                                   int link, const JointLog& motion, const Eigen::MatrixXd& extra,
                                   const std::optional<ParallelFilter>& parallel_filter, const std::string& which);

// Minimum-norm least squares of A x = b with the unknowns' identifiability
// (least_squares.h), through the R factor of [A b] (same row space, p + 1
// rows instead of m).
struct MinNormSolution {
  LeastSquaresSolution ls;   // rank, identifiable, reasons
  Eigen::VectorXd x;         // minimum-norm solution, every entry finite (p)
  Eigen::MatrixXd pseudo_inverse_factor;  // F (p × rank): (AᵀA)⁺ = F Fᵀ in the determined directions
  Eigen::VectorXd variance;  // diag((AᵀA)⁺) = row norms² of F (p)
  double residual2 = 0.0;    // ‖A x − b‖²
};
MinNormSolution SolveMinNorm(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const std::vector<std::string>& names);

}  // namespace idbench::internal
