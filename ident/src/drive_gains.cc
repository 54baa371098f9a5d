#include "idbench/ident/drive_gains.h"

#include "idbench/ident/residual_covariance.h"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/ident/least_squares.h"
#include "idbench/ident/linear_estimator.h"
#include "link_equations.h"

namespace idbench {
namespace {

using internal::MinNormSolution;
using internal::SolveMinNorm;

// Columns of one log's equations, rows interleaved by joint (s·n + j):
// the base regressor (n_base), the last link's 10 standard columns
// [m, mcx, …, Izz] (payload; used in the loaded log only), and the current
// of the row's joint in that joint's column (n_dof).
Eigen::MatrixXd StackGainEquations(const RobotModel& model, const FrictionModel& friction,
                                   const BaseParameters& base, const CurrentLog& log, const char* which) {
  const int n = model.n_dof();
  const int n_samples = log.motion.n_samples();
  if (log.current.rows() != n_samples || log.current.cols() != n) {
    throw std::invalid_argument(std::string(which) + " log: expected currents of " + std::to_string(n_samples) + "x" +
                                std::to_string(n) + ", got " + std::to_string(log.current.rows()) + "x" +
                                std::to_string(log.current.cols()));
  }
  Eigen::MatrixXd currents = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_samples) * n, n);
  for (int s = 0; s < n_samples; ++s) {
    for (int j = 0; j < n; ++j) currents(static_cast<Eigen::Index>(s) * n + j, j) = log.current(s, j);
  }
  return internal::StackLinkEquations(model, friction, &base, model.n_links() - 1, log.motion, currents,
                                      log.parallel_filter, which);
}

// Per-joint RMS of a stacked residual, and ‖r‖/‖ref‖.
void ResidualStatistics(const Eigen::VectorXd& r, const Eigen::VectorXd& reference, int n_dof, Eigen::VectorXd* rms,
                        double* relative) {
  *rms = JointRms(r, n_dof);
  const double ref = reference.norm();
  *relative = ref > 0.0 ? r.norm() / ref : std::numeric_limits<double>::infinity();
}

// Both logs' equations stacked, [W, payload columns, −diag(i)] x = b for the
// unknowns x = [β; φ'; K] (p of them): the unloaded log's rows first.
struct GainEquations {
  Eigen::MatrixXd A;           // (m_u + m_l) × p
  Eigen::VectorXd b;           // (m_u + m_l): −m_payload × the mass column on the loaded rows
  Eigen::MatrixXd W_unloaded;  // the unloaded log's base regressor (m_u × n_base)
  Eigen::Index m_u = 0, m_l = 0;
};
GainEquations StackGainSystem(const RobotModel& model, const DriveGainOptions& options, const BaseParameters& base,
                              const CurrentLog& unloaded, const CurrentLog& loaded, int p) {
  const int n = model.n_dof();
  const int n_base = base.n_base();
  const int n_payload = kInertialParametersPerLink - 1;
  const Eigen::MatrixXd U = StackGainEquations(model, options.friction, base, unloaded, "unloaded");
  const Eigen::MatrixXd L = StackGainEquations(model, options.friction, base, loaded, "loaded");
  GainEquations eq;
  eq.m_u = U.rows(), eq.m_l = L.rows();
  const Eigen::Index n_equations = eq.m_u + eq.m_l;
  if (n_equations <= p) {
    throw std::invalid_argument("drive gains: " + std::to_string(n_equations) + " equations for " +
                                std::to_string(p) + " unknowns; record longer logs");
  }
  const int mass_col = n_base, payload_col = n_base + 1;  // in U, L
  eq.A = Eigen::MatrixXd::Zero(n_equations, p);
  eq.b = Eigen::VectorXd::Zero(n_equations);
  eq.A.topLeftCorner(eq.m_u, n_base) = U.leftCols(n_base);
  eq.A.topRightCorner(eq.m_u, n) = -U.rightCols(n);
  eq.A.bottomLeftCorner(eq.m_l, n_base) = L.leftCols(n_base);
  eq.A.block(eq.m_u, n_base, eq.m_l, n_payload) = L.middleCols(payload_col, n_payload);
  eq.A.bottomRightCorner(eq.m_l, n) = -L.rightCols(n);
  eq.b.tail(eq.m_l) = -options.payload_mass * L.col(mass_col);
  eq.W_unloaded = U.leftCols(n_base);
  return eq;
}

// Gauss–Newton on the linear model in current units, the noise where it is
// measured: e = (W β + Y φ' + M y)/K_j − i per row of joint j (the first
// n_head unknowns are [β; φ'], the last n the gains K). Started at *x;
// noise-free data are a fixed point. *solution: the solve at the estimate
// (its Jacobian *J, for σ) with the residual *e and ‖e‖².
void RefineInCurrentUnits(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int n,
                          const std::vector<std::string>& names, Eigen::VectorXd* x, MinNormSolution* solution,
                          Eigen::MatrixXd* J_at_estimate, Eigen::VectorXd* e_at_estimate) {
  const Eigen::Index p = A.cols(), n_head = p - n;
  auto current_residual = [&](const Eigen::VectorXd& xk, Eigen::MatrixXd* J) {
    const Eigen::VectorXd torque = A.leftCols(n_head) * xk.head(n_head) - b;  // W β + Y φ' + M y
    Eigen::VectorXd e(A.rows());
    if (J) J->setZero(A.rows(), p);
    for (Eigen::Index r = 0; r < A.rows(); ++r) {
      const int j = static_cast<int>(r % n);
      const double K = xk[n_head + j], current = -A(r, n_head + j);
      e[r] = torque[r] / K - current;
      if (J) {
        J->row(r).head(n_head) = A.row(r).head(n_head) / K;
        (*J)(r, n_head + j) = -torque[r] / (K * K);
      }
    }
    return e;
  };
  Eigen::MatrixXd J;
  constexpr int kMaxIterations = 30;
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::VectorXd e = current_residual(*x, &J);
    const MinNormSolution step = SolveMinNorm(J, -e, names);
    *x += step.x;
    if (step.x.tail(n).cwiseQuotient(x->tail(n)).cwiseAbs().maxCoeff() < 1e-13) break;
  }
  const Eigen::VectorXd e = current_residual(*x, &J);
  *solution = SolveMinNorm(J, e, names);  // for σ: the Jacobian at the estimate
  solution->residual2 = e.squaredNorm();
  *J_at_estimate = std::move(J);
  *e_at_estimate = e;
}

// The estimate's status and message: gains the logs do not determine (from
// the solve's reasons), the payload not seen above the noise, or torques K·i
// far from (or against) what the robot file predicts.
void JudgeGains(const std::vector<std::string>& reasons, DriveGainEstimate* out) {
  const int n = static_cast<int>(out->gains.size());
  const size_t first_gain = out->identifiable.size() - static_cast<size_t>(n);
  // Gains the logs do not determine: a status, with the reason.
  std::string missing;
  for (int j = 0; j < n; ++j) {
    const size_t c = first_gain + static_cast<size_t>(j);
    if (out->identifiable[c]) continue;
    missing += (missing.empty() ? "" : "; ") + reasons[c];
  }
  if (!missing.empty()) {
    out->status = DriveGainStatus::kNotIdentifiable;
    out->message = "the logs do not determine every drive gain (" + missing +
                   "): the loaded motion must move the payload so that its mass shows in every joint's torque, and "
                   "each joint must move in both logs";
    return;
  }

  // Gains the data cannot carry: the payload not seen above the noise, or
  // torques K·i far from (or against) what the robot file predicts.
  char text[768];
  if (!(out->payload_signal_to_noise >= DriveGainOptions::kMinPayloadSignalToNoise)) {
    std::snprintf(text, sizeof(text),
                  "the payload's effect is not seen in the data: its torque in the loaded log is %.3g times that "
                  "log's residual (at least %g expected), so the gains are not determined (they came out at %.3g to "
                  "%.3g N m/A); check that the loaded log was recorded with the payload fixed to the last link, that "
                  "the payload mass is right, that the two logs are different recordings, and cut rest phases where "
                  "the drives idle (time_window, loaded_time_window)",
                  out->payload_signal_to_noise, DriveGainOptions::kMinPayloadSignalToNoise,
                  out->gains.cwiseAbs().minCoeff(), out->gains.cwiseAbs().maxCoeff());
    out->status = DriveGainStatus::kNotObserved;
    out->message = text;
  } else if (!(std::abs(out->torque_scale) >= 1.0 / DriveGainOptions::kMaxTorqueScale &&
               std::abs(out->torque_scale) <= DriveGainOptions::kMaxTorqueScale)) {
    // Near 0 (of either sign: the same log twice gives ±1e-13 by rounding)
    // or far from 1: not the payload's effect.
    std::snprintf(text, sizeof(text),
                  "the payload's effect is not seen in the data as its mass implies: the gains make the unloaded "
                  "log's torques %.3g times what the robot file predicts (%g to %g expected); check that the loaded "
                  "log was recorded with the payload fixed to the last link, the payload mass, that the two logs are "
                  "different recordings, and the robot file's masses",
                  out->torque_scale, 1.0 / DriveGainOptions::kMaxTorqueScale, DriveGainOptions::kMaxTorqueScale);
    out->status = DriveGainStatus::kNotObserved;
    out->message = text;
  } else if (out->torque_scale < 0.0) {  // |scale| in range, against the file
    std::snprintf(text, sizeof(text),
                  "the gains turn the unloaded log's torques against the robot file's prediction (scale %.3g): the "
                  "two logs look swapped (the log with the payload must be the loaded one), or every current is "
                  "logged with the opposite sign",
                  out->torque_scale);
    out->status = DriveGainStatus::kNotObserved;
    out->message = text;
  }
}

}  // namespace

const std::vector<std::string>& PayloadParameterNames() {
  static const std::vector<std::string> names{"mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"};
  return names;
}

bool DriveGainOptions::IsValid(std::string* why) const {
  if (!(payload_mass > 0.0 && payload_mass <= kMaxPayloadMass)) {
    if (why) {
      char text[160];
      std::snprintf(text, sizeof(text), "expected a payload mass in (0, %g] kg, got %g", kMaxPayloadMass, payload_mass);
      *why = text;
    }
    return false;
  }
  return true;
}

DriveGainEstimate EstimateDriveGains(const RobotModel& model, const CurrentLog& unloaded, const CurrentLog& loaded,
                                     const DriveGainOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("drive gains: " + why);
  const int n = model.n_dof();
  DriveGainEstimate out;
  out.base = ComputeBaseParameters(model, options.friction, options.base);
  const int n_base = out.base.n_base();
  const int n_payload = kInertialParametersPerLink - 1;
  const int p = n_base + n_payload + n;  // unknowns x = [β; φ'; K]

  // Both logs' equations: [W, payload columns, −diag(i)] x = b.
  const GainEquations eq = StackGainSystem(model, options, out.base, unloaded, loaded, p);
  const Eigen::MatrixXd& A = eq.A;
  const Eigen::VectorXd& b = eq.b;
  const Eigen::Index m_u = eq.m_u, m_l = eq.m_l;
  out.n_equations = m_u + m_l;

  // Names of the unknowns, for the messages.
  out.unknown_names = out.base.names;
  for (const std::string& name : PayloadParameterNames()) out.unknown_names.push_back("payload " + name);
  for (int j = 1; j <= n; ++j) out.unknown_names.push_back("K" + std::to_string(j));

  // 1. Linear least squares in torque units (Gautier & Briot's equations as
  //    written). Noise in the currents sits in A's K columns, so this shrinks
  //    K (errors in variables: the homogeneous unloaded rows reward a small
  //    K by (σ_i K)² per row); it is the start, and says what is identifiable.
  MinNormSolution solution = SolveMinNorm(A, b, out.unknown_names);
  out.rank = solution.ls.rank;
  out.identifiable = solution.ls.identifiable;
  Eigen::VectorXd x = solution.x;
  const Eigen::Index n_head = n_base + n_payload;
  const bool gains_found = (x.tail(n).array().abs() > 0.0).all() && x.allFinite();

  // 2. Gauss–Newton in current units (RefineInCurrentUnits), from the linear
  //    estimate.
  Eigen::MatrixXd J = A;                  // the rows σ comes from, and their residual
  Eigen::VectorXd J_residual = A * x - b;
  if (gains_found) RefineInCurrentUnits(A, b, n, out.unknown_names, &x, &solution, &J, &J_residual);
  const Eigen::VectorXd x_full = x;  // the undetermined entries as the minimum-norm steps left them
  for (size_t c = 0; c < out.identifiable.size(); ++c) {
    if (!out.identifiable[c]) x[static_cast<Eigen::Index>(c)] = std::numeric_limits<double>::quiet_NaN();
  }
  out.beta = x.head(n_base);
  out.payload = x.segment(n_base, n_payload);
  out.gains = x.tail(n);

  // σ from the residual as it is (residual_covariance.h): the sandwich with
  // G = (JᵀJ)⁺ (the linear A if no refinement) over the two logs' samples;
  // σ_white² = ‖e‖²/(m − rank) G_kk.
  const double sigma2 = solution.residual2 / static_cast<double>(out.n_equations - out.rank);
  const Eigen::MatrixXd G = solution.pseudo_inverse_factor * solution.pseudo_inverse_factor.transpose();
  const Eigen::MatrixXd covariance = StackedSandwichCovariance(J, J_residual, n, G, sigma2, &out.covariance_method);
  out.sigma = out.sigma_white = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (int j = 0; j < n; ++j) {
    if (!out.identifiable[static_cast<size_t>(n_head + j)]) continue;
    out.sigma[j] = std::sqrt(std::max(0.0, covariance(n_head + j, n_head + j)));
    out.sigma_white[j] = std::sqrt(sigma2 * solution.variance[n_head + j]);
  }

  // Each log's torque residual W β + Y φ' + M y − K·i (the undetermined
  // unknowns' values do not change it: they are in the null space of A).
  const Eigen::VectorXd r = A * x_full - b;
  const Eigen::VectorXd torque = -(A.rightCols(n) * x_full.tail(n));  // K·i
  ResidualStatistics(r.head(m_u), torque.head(m_u), n, &out.unloaded_rms, &out.unloaded_relative_error);
  ResidualStatistics(r.tail(m_l), torque.tail(m_l), n, &out.loaded_rms, &out.loaded_relative_error);

  // Whether the payload's effect is observed: the torques K·i of the unloaded
  // log against the robot file's prediction W β_file (s = ⟨K·i, W β_file⟩ /
  // ‖W β_file‖²: ≈ 1 when the gains are right, whatever each drive's current
  // sign), and the payload's torque in the loaded log against that log's
  // residual.
  const Eigen::VectorXd beta_file = out.base.combination * StandardParameters(model, options.friction);
  const Eigen::VectorXd tau_file = eq.W_unloaded * beta_file;
  out.torque_scale = tau_file.squaredNorm() > 0.0 ? torque.head(m_u).dot(tau_file) / tau_file.squaredNorm()
                                                   : std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd payload_torque = A.block(m_u, n_base, m_l, n_payload) * x_full.segment(n_base, n_payload) - b.tail(m_l);
  out.payload_signal_to_noise = payload_torque.norm() / r.tail(m_l).norm();

  // The verdict: determined, observed, consistent with the robot file.
  JudgeGains(solution.ls.reason, &out);
  return out;
}

}  // namespace idbench
