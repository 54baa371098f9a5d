#include "idbench/ident/closed_loop_estimators.h"

#include <Eigen/QR>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <tuple>
#include <limits>
#include <utility>
#include <stdexcept>

#include "idbench/engine/closed_loop.h"
#include "idbench/ident/base_parameter_dynamics.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/ident/residual_covariance.h"

namespace idbench {

bool ClosedLoopEstimatorOptions::IsValid(int n_dof, std::string* why) const {
  if (max_iterations < 1 || max_iterations > kMaxIterations) {
    if (why) *why = "max_iterations: expected 1 to 1000, got " + std::to_string(max_iterations);
    return false;
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    if (why) *why = "tolerance: expected a finite value > 0, got " + std::to_string(tolerance);
    return false;
  }
  std::string controller_why;
  if (!controller.IsValid(n_dof, &controller_why)) {
    if (why) *why = "controller: " + controller_why;
    return false;
  }
  return true;
}

namespace {

// The log's sample period T and its first sample's index t[0]/T, checking
// that it is sampled uniformly at whole multiples of T.
std::pair<double, int> UniformSamples(const JointLog& log) {
  const Eigen::Index n = log.t.size();
  if (n < 3) throw std::invalid_argument("closed-loop estimator: expected at least 3 samples, got " + std::to_string(n));
  const double period = (log.t[n - 1] - log.t[0]) / static_cast<double>(n - 1);
  const double first = std::round(log.t[0] / period);
  for (Eigen::Index s = 0; s < n; ++s) {
    if (!(period > 0.0) || !(std::abs(log.t[s] - (first + s) * period) <= 1e-6 * period)) {
      throw std::invalid_argument("closed-loop estimator: expected a log sampled at the controller's period from "
                                  "t = 0 (its ends may be trimmed), sample " + std::to_string(s) + " is at t = " +
                                  std::to_string(log.t[s]) + " s");
    }
  }
  return {period, static_cast<int>(first)};
}

// Where a log's samples sit on the controller's clock: its period T, its
// first sample's index, and the re-simulation's length (checked against the
// reference's).
struct LogClock {
  double period = 0.0;
  int first = 0;
  int n_samples = 0;
  double duration = 0.0;
};

LogClock ClockOf(const JointLog& log, const Trajectory& reference) {
  LogClock clock;
  std::tie(clock.period, clock.first) = UniformSamples(log);
  clock.n_samples = log.n_samples();
  clock.duration = std::min((clock.first + clock.n_samples) * clock.period, reference.duration());
  if (std::lround(clock.duration / clock.period) < clock.first + clock.n_samples) {
    throw std::invalid_argument("closed-loop estimator: the reference lasts " + std::to_string(reference.duration()) +
                                " s, the log to " + std::to_string(log.t[clock.n_samples - 1]) + " s");
  }
  return clock;
}

// The closed loop re-simulated with the estimate β (its forward dynamics from
// the regressor), one step per sample, noise-free sensors at the log's rate;
// its states at the log's samples (t, q, qd, qdd; no τ), q̈ at a sample the
// mean of the two holds' when torque_held (ClosedLoopEstimatorOptions).
// Throws std::runtime_error when it fails (β's mass matrix not positive
// definite, a diverging loop).
JointLog SimulateAtLogSamples(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                              const Eigen::VectorXd& beta, const Trajectory& reference, const LogClock& clock,
                              JointController* controller, bool torque_held) {
  SensorOptions exact;
  exact.rate_hz = 1.0 / clock.period;
  BaseParameterDynamics dynamics(model, friction, base, beta);
  ClosedLoopLog simulated = RunClosedLoop(reference, clock.duration, clock.period, controller, exact,
                                          [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                              const Eigen::VectorXd& t, Eigen::VectorXd* qdd) {
                                            dynamics.Accelerations(q, qd, t, qdd);
                                          });
  JointLog& states = simulated.log;
  if (torque_held) {
    // At sample k > 0: ½ (q̈ under τ_{k−1} + q̈ under τ_k), the state the same.
    Eigen::VectorXd qdd_before;
    for (Eigen::Index k = std::max(1, clock.first); k < clock.first + clock.n_samples; ++k) {
      dynamics.Accelerations(states.q.row(k).transpose(), states.qd.row(k).transpose(),
                             states.tau.row(k - 1).transpose(), &qdd_before);
      states.qdd.row(k) = 0.5 * (states.qdd.row(k) + qdd_before.transpose());
    }
  }
  states.t = states.t.segment(clock.first, clock.n_samples).eval();
  for (Eigen::MatrixXd* m : {&states.q, &states.qd, &states.qdd}) {
    *m = m->middleRows(clock.first, clock.n_samples).eval();
  }
  return std::move(states);
}

void CheckSizes(const RobotModel& model, const BaseParameters& base, const JointLog& log, const Trajectory& reference,
                const Eigen::VectorXd& beta) {
  const int n_dof = model.n_dof();
  if (log.n_dof() != n_dof || reference.n_dof() != n_dof) {
    throw std::invalid_argument("closed-loop estimator: the robot has " + std::to_string(n_dof) + " joints, the log " +
                                std::to_string(log.n_dof()) + ", the reference " + std::to_string(reference.n_dof()));
  }
  if (beta.size() != base.n_base()) {
    throw std::invalid_argument("closed-loop estimator: expected " + std::to_string(base.n_base()) +
                                " base parameters, got " + std::to_string(beta.size()));
  }
}

}  // namespace

double ClosedLoopPositionError(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                               const JointLog& log, const Trajectory& reference, const Eigen::VectorXd& beta,
                               const JointControllerOptions& controller_options) {
  std::string why;
  if (!controller_options.IsValid(model.n_dof(), &why)) throw std::invalid_argument("closed-loop estimator: " + why);
  CheckSizes(model, base, log, reference, beta);
  const LogClock clock = ClockOf(log, reference);
  JointController controller(controller_options, model, clock.period);
  const JointLog states =
      SimulateAtLogSamples(model, friction, base, beta, reference, clock, &controller, /*torque_held=*/false);
  const double size = log.q.norm();
  if (!(size > 0.0)) throw std::invalid_argument("closed-loop estimator: the log's positions are all zero");
  return (states.q - log.q).norm() / size;
}

ClosedLoopEstimate EstimateClosedLoop(const RobotModel& model, const FrictionModel& friction,
                                      const BaseParameters& base, const JointLog& log, const Trajectory& reference,
                                      const Eigen::VectorXd& beta_initial, const ClosedLoopEstimatorOptions& options) {
  const int n_dof = model.n_dof();
  std::string why;
  if (!options.IsValid(n_dof, &why)) throw std::invalid_argument("closed-loop estimator: " + why);
  CheckSizes(model, base, log, reference, beta_initial);
  const bool iv = options.method == ClosedLoopMethod::kInstrumentalVariables;
  if (iv && !log.has_derivatives()) {
    throw std::invalid_argument("closed-loop estimator: instrumental variables need the log's qd and qdd");
  }
  const LogClock clock = ClockOf(log, reference);
  JointController controller(options.controller, model, clock.period);
  // The log's own equations (IV), stacked and filtered as the simulations' will be.
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  if (iv) StackEquations(model, friction, base, log, options.parallel_filter, &W, &tau);

  ClosedLoopEstimate out;
  out.beta = beta_initial;
  out.sigma = Eigen::VectorXd::Constant(base.n_base(), std::numeric_limits<double>::infinity());
  const int p = base.n_base();
  for (int k = 1; k <= options.max_iterations; ++k) {
    // Simulate the closed loop with the current estimate.
    JointLog states;
    try {
      states =
          SimulateAtLogSamples(model, friction, base, out.beta, reference, clock, &controller, options.torque_held);
    } catch (const std::runtime_error& e) {
      out.message = "diverged at iteration " + std::to_string(k) + ": re-simulating the estimate failed (" +
                    e.what() + ")";
      return out;
    }
    // The log's samples of the simulation, with the MEASURED torques: its
    // equations are the regressor of the simulated states against them.
    states.tau = log.tau;
    Eigen::MatrixXd Ws;
    Eigen::VectorXd tau_s;
    StackEquations(model, friction, base, states, options.parallel_filter, &Ws, &tau_s);
    if (!iv) tau = tau_s;
    Eigen::VectorXd beta_next;
    if (iv) {
      // Zᵀ W β = Zᵀ τ with Z = Ws; σ² of the IV estimator s² (ZᵀW)⁻¹ ZᵀZ (WᵀZ)⁻¹.
      const Eigen::MatrixXd ZtW = Ws.transpose() * W;
      const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(ZtW);
      beta_next = qr.solve(Ws.transpose() * tau);
      const Eigen::VectorXd r = tau - W * beta_next;
      const double s2 = r.squaredNorm() / std::max<Eigen::Index>(1, tau.size() - p);
      const Eigen::MatrixXd A = qr.solve(Eigen::MatrixXd::Identity(p, p));  // (ZᵀW)⁻¹
      const Eigen::MatrixXd white = s2 * A * (Ws.transpose() * Ws) * A.transpose();
      out.sigma_white = white.diagonal().cwiseMax(0.0).cwiseSqrt();
      const Eigen::MatrixXd cov =
          StackedInstrumentSandwich(Ws, r, n_dof, A, white, &out.covariance, BlockBias::kExtrapolated);
      out.sigma = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
    } else {
      LinearFit fit = SolveOls(Ws, tau, n_dof);
      ApplyStackedScoreCovariance(Ws, tau, n_dof, &fit, 0, BlockBias::kExtrapolated);
      beta_next = fit.beta;
      out.sigma = fit.sigma;
      out.sigma_white = fit.sigma_white;
      out.covariance = fit.covariance_method;
    }
    out.last_change = (beta_next - out.beta).norm() / std::max(out.beta.norm(), 1e-300);
    out.beta = beta_next;
    out.iterations = k;
    if (!out.beta.allFinite()) {
      out.message = "diverged at iteration " + std::to_string(k) + ": the estimate is not finite";
      return out;
    }
    if (out.last_change <= options.tolerance) {
      out.converged = true;
      char text[160];
      std::snprintf(text, sizeof(text), "converged in %d iterations (relative change %.3g)", k, out.last_change);
      out.message = text;
      return out;
    }
  }
  char text[200];
  std::snprintf(text, sizeof(text), "not converged: %d iterations (max_iterations), last relative change %.3g",
                options.max_iterations, out.last_change);
  out.message = text;
  return out;
}

}  // namespace idbench
