// Estimators for a robot identified under its own feedback control. The
// controller reacts to the position noise, so the states a log's regressor is
// built from are correlated with the torque's error, and least squares is
// biased. Both estimators here re-simulate the closed loop (the controller,
// the reference, the estimate's forward dynamics: closed_loop.h,
// base_parameter_dynamics.h), whose states carry no noise, and iterate:
//   IV (instrumental variables; Janot, Vandanjon & Gautier, IEEE TCST 22(1),
//     2014): the instruments Z are the base regressor of the simulated states;
//     β_{k+1} solves Zᵀ W β = Zᵀ τ, W the regressor of the log's own states;
//   DIDIM (direct and inverse dynamic identification model; Gautier, Janot &
//     Vandanjon, IEEE TCST 21(3), 2013): β_{k+1} is the least squares of the
//     measured τ on the regressor of the simulated states.
// Both stop when ‖β_{k+1} − β_k‖ ≤ tolerance ‖β_k‖. The simulated
// samples' equations are stacked (and filtered) as the log's are, row for row.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "idbench/engine/joint_controller.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/trajectory.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"

namespace idbench {

enum class ClosedLoopMethod { kInstrumentalVariables, kDidim };

struct ClosedLoopEstimatorOptions {
  ClosedLoopMethod method = ClosedLoopMethod::kDidim;
  JointControllerOptions controller;  // the robot's controller, as in the experiment
  // Parallel filtering of every stacked regressor and τ (the log's and the
  // simulations' alike, joint_torque_identifier.h), for a log whose qd, qdd
  // were estimated by that filter; none: the log's qd, qdd as they are.
  std::optional<ParallelFilter> parallel_filter;
  // The log's τ at a sample is the mean of the hold ending there and the one
  // starting there (logs' held torques, HeldTorqueSource): the simulated q̈ at
  // a sample is then read the same way, the mean of the accelerations under
  // both holds, so that the simulated regressor pairs with that τ (without
  // it, DIDIM stays ~1 % off noise-free). The log's first sample (t = 0)
  // keeps its own.
  bool torque_held = false;
  int max_iterations = 30;            // re-simulations, at most kMaxIterations
  double tolerance = 1e-8;            // relative change of β that counts as converged
  static constexpr int kMaxIterations = 1000;

  // *why names the field (max_iterations, tolerance, controller's kp, …).
  bool IsValid(int n_dof, std::string* why) const;
};

struct ClosedLoopEstimate {
  Eigen::VectorXd beta;   // base parameters (n_base)
  // Their σ at the last iteration (n_base), from the residual as it is: the
  // batch-means sandwich of the iteration's estimator (residual_covariance.h;
  // IV: (ZᵀW)⁻¹ Ω (WᵀZ)⁻¹ with the scores Z_tᵀ e_t), Ω extrapolated past its
  // block length (BlockBias::kExtrapolated: the residual is mostly the loop's
  // reaction to the position noise, whose block sums telescope).
  Eigen::VectorXd sigma;
  Eigen::VectorXd sigma_white;    // the same as if the residual were white (n_base)
  CovarianceSummary covariance;   // how sigma was computed (blocks, n_eff)
  int iterations = 0;     // re-simulations run
  bool converged = false;
  double last_change = 0.0;  // ‖β_k − β_{k−1}‖ / ‖β_{k−1}‖ of the last iteration
  std::string message;       // converged in k iterations, or why not (diverged, iteration limit)
};

// Estimates β from a log sampled at the controller's period T (its samples at
// t = k·T, k from t[0]/T: a time window may have cut its start), starting at beta_initial
// (e.g. OLS's or the robot file's). `model` is the robot description: its
// regressor, and the controller's feed-forward when it has one. IV needs the
// log's qd, qdd (read or estimated); DIDIM uses t and τ only. Throws
// std::invalid_argument when the options, log, reference and model do not
// fit together. A re-simulation that fails (the estimate's mass matrix not
// positive definite, a diverging loop) ends the iteration with converged
// false and the message saying so; beta is then the last estimate.
ClosedLoopEstimate EstimateClosedLoop(const RobotModel& model, const FrictionModel& friction,
                                      const BaseParameters& base, const JointLog& log, const Trajectory& reference,
                                      const Eigen::VectorXd& beta_initial, const ClosedLoopEstimatorOptions& options);

// The relative position error of an estimate (BIRDy's position metric): the
// closed loop re-simulated with β as the estimators re-simulate it (the
// controller, the reference, β's forward dynamics) against the log's measured
// positions, ‖Q_log − Q_sim‖_F / ‖Q_log‖_F over the log's samples. Throws
// std::invalid_argument as EstimateClosedLoop does, std::runtime_error when
// the re-simulation fails (β is no mechanism, the loop diverges).
double ClosedLoopPositionError(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                               const JointLog& log, const Trajectory& reference, const Eigen::VectorXd& beta,
                               const JointControllerOptions& controller);

}  // namespace idbench
