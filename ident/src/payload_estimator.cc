#include "idbench/ident/payload_estimator.h"

#include "idbench/ident/residual_covariance.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "idbench/engine/inverse_dynamics.h"
#include "link_equations.h"
#include "quadratic_sdp.h"

namespace idbench {
namespace {

using Matrix10 = Eigen::Matrix<double, 10, 10>;
using Vector10 = Eigen::Matrix<double, 10, 1>;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// φ's inertia entries [Ixx, Ixy, Iyy, Ixz, Iyz, Izz] (4..9) for the
// quantities' order [Ixx, Ixy, Ixz, Iyy, Iyz, Izz]: quantity 4 + k is φ entry
// kInertiaOfQuantity[k].
constexpr int kInertiaOfQuantity[6] = {4, 5, 7, 6, 8, 9};
// S(h) = hᵀh 𝟙 − h hᵀ in the quantities' order, and ∂S/∂h (rows xx, xy, xz, yy, yz, zz).
Eigen::Matrix<double, 6, 1> ParallelAxis(const Eigen::Vector3d& h) {
  return (Eigen::Matrix<double, 6, 1>() << h.y() * h.y() + h.z() * h.z(), -h.x() * h.y(), -h.x() * h.z(),
          h.x() * h.x() + h.z() * h.z(), -h.y() * h.z(), h.x() * h.x() + h.y() * h.y())
      .finished();
}
Eigen::Matrix<double, 6, 3> ParallelAxisJacobian(const Eigen::Vector3d& h) {
  Eigen::Matrix<double, 6, 3> d;
  d << 0, 2 * h.y(), 2 * h.z(),  //
      -h.y(), -h.x(), 0,         //
      -h.z(), 0, -h.x(),         //
      2 * h.x(), 0, 2 * h.z(),   //
      0, -h.z(), -h.y(),         //
      2 * h.x(), 2 * h.y(), 0;
  return d;
}

// One log's torque rows (and the robot file's prediction) as stacked columns.
Eigen::MatrixXd StackedTorques(const RobotModel& model, const TorqueLog& log, bool with_model_torque,
                               const std::string& which) {
  const int n = model.n_dof();
  const JointLog& m = log.motion;
  const int n_samples = m.n_samples();
  if (m.tau.rows() != n_samples || m.tau.cols() != n || m.q.cols() != n || m.qd.rows() != n_samples ||
      m.qd.cols() != n || m.qdd.rows() != n_samples || m.qdd.cols() != n) {
    throw std::invalid_argument(which + " log: expected q, qd, qdd and tau of " + std::to_string(n) + " joints for " +
                                std::to_string(n_samples) + " samples (robot '" + model.name() + "')");
  }
  Eigen::MatrixXd out(static_cast<Eigen::Index>(n_samples) * n, with_model_torque ? 2 : 1);
  RobotData data(model);
  Eigen::VectorXd tau_model;
  for (int s = 0; s < n_samples; ++s) {
    const Eigen::Index r0 = static_cast<Eigen::Index>(s) * n;
    out.col(0).segment(r0, n) = m.tau.row(s).transpose();
    if (!with_model_torque) continue;
    const Eigen::VectorXd q = m.q.row(s).transpose(), qd = m.qd.row(s).transpose(), qdd = m.qdd.row(s).transpose();
    tau_model = InverseDynamics(model, q, qd, qdd, &data);
    AddJointDynamicsTorque(model, qd, qdd, &tau_model);
    out.col(1).segment(r0, n) = tau_model;
  }
  return out;
}

// The consistent estimate: argmin ‖R (φ − φ̂)‖² subject to J(φ) ≻ 0, with
// R Rᵀ's inverse the (unscaled) covariance M. Returns φ̂ when it is
// consistent already.
InertialParameters ProjectOntoConsistent(const InertialParameters& phi_ls, const Matrix10& M, double* distance2) {
  *distance2 = 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(PseudoInertia(phi_ls));
  if (eig.eigenvalues().minCoeff() > 0.0) return phi_ls;
  const Eigen::LLT<Matrix10> llt(M);
  if (llt.info() != Eigen::Success) throw std::runtime_error("payload: covariance not positive definite");
  internal::QuadraticSdp problem;
  problem.R = llt.matrixL().solve(Matrix10::Identity());  // L⁻¹: ‖L⁻¹ x‖² = xᵀ M⁻¹ x
  problem.z = problem.R * phi_ls;
  internal::LmiBlock block;
  block.C = Eigen::Matrix4d::Zero();
  for (int i = 0; i < kInertialParametersPerLink; ++i) {
    block.variables.push_back(i);
    block.B.push_back(PseudoInertia(Vector10::Unit(i)));
  }
  problem.blocks.push_back(std::move(block));
  internal::QuadraticSdpOptions options;
  options.objective_floor = 1e-12 * problem.z.squaredNorm();
  // A consistent start: a point mass of φ̂'s mass (or 1 kg) at the origin, with a small ball's inertia.
  const double mass = phi_ls[0] > 0.0 ? phi_ls[0] : 1.0;
  options.start = Vector10::Zero();
  options.start[0] = mass;
  const double ball = 1e-3 * mass;  // [kg m²]
  options.start[4] = options.start[6] = options.start[9] = ball;
  const internal::QuadraticSdpSolution solution = internal::SolveQuadraticSdp(problem, options);
  *distance2 = solution.objective;
  return solution.u;
}

// The quantity whose σ is largest against its scale.
int WorstRelativeSigma(const PayloadBody& body, const Eigen::Matrix<double, 10, 1>& sigma) {
  int worst = 0;
  for (int k = 1; k < 10; ++k) {
    if (sigma[k] / PayloadQuantityScale(body, k) > sigma[worst] / PayloadQuantityScale(body, worst)) worst = k;
  }
  return worst;
}

// "a, b and c".
std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k) out += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return out;
}

}  // namespace

double PayloadQuantityScale(const PayloadBody& body, int k) {
  const double half_trace = 0.5 * (body.I_Pcm_B[0] + body.I_Pcm_B[3] + body.I_Pcm_B[5]);
  if (k == 0) return body.mass;
  if (k < 4) return std::max(body.p_BoPcm_B.norm(), std::sqrt(std::max(half_trace, 0.0) / body.mass));
  return half_trace;
}

const char* PayloadStatusName(PayloadStatus status) {
  switch (status) {
    case PayloadStatus::kEstimated: return "estimated";
    case PayloadStatus::kNotIdentifiable: return "not identifiable";
    case PayloadStatus::kPoorlyDetermined: return "poorly determined";
    case PayloadStatus::kNotPhysical: return "not physical";
  }
  return "?";
}

const std::vector<std::string>& PayloadQuantityNames() {
  static const std::vector<std::string> names{"mass", "com_x", "com_y", "com_z", "Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz"};
  return names;
}

const std::vector<std::string>& PayloadInertialParameterNames() {
  static const std::vector<std::string> names{"m",      "mcx",    "mcy",    "mcz",    "Ixx_Bo",
                                              "Ixy_Bo", "Iyy_Bo", "Ixz_Bo", "Iyz_Bo", "Izz_Bo"};
  return names;
}

PayloadBody PayloadBodyFromParameters(const InertialParameters& phi) {
  PayloadBody body;
  body.mass = phi[0];
  const Eigen::Vector3d h = phi.segment<3>(1);
  body.p_BoPcm_B = h / body.mass;
  const Eigen::Matrix<double, 6, 1> S = ParallelAxis(h);
  for (int k = 0; k < 6; ++k) body.I_Pcm_B[k] = phi[kInertiaOfQuantity[k]] - S[k] / body.mass;
  return body;
}

InertialParameters PayloadParametersFromBody(const PayloadBody& body) {
  InertialParameters phi;
  const Eigen::Vector3d h = body.mass * body.p_BoPcm_B;
  phi[0] = body.mass;
  phi.segment<3>(1) = h;
  const Eigen::Matrix<double, 6, 1> S = ParallelAxis(h);
  for (int k = 0; k < 6; ++k) phi[kInertiaOfQuantity[k]] = body.I_Pcm_B[k] + S[k] / body.mass;
  return phi;
}

Eigen::Matrix<double, 10, 1> PayloadQuantities(const PayloadBody& body) {
  Vector10 out;
  out << body.mass, body.p_BoPcm_B, body.I_Pcm_B;
  return out;
}

Eigen::Matrix<double, 10, 10> PayloadQuantityJacobian(const InertialParameters& phi) {
  const double m = phi[0];
  const Eigen::Vector3d h = phi.segment<3>(1);
  Matrix10 J = Matrix10::Zero();
  J(0, 0) = 1.0;
  // c = h/m.
  J.block<3, 3>(1, 1) = Eigen::Matrix3d::Identity() / m;
  J.block<3, 1>(1, 0) = -h / (m * m);
  // I_Pcm = I_Bo − S(h)/m.
  J.block<6, 1>(4, 0) = ParallelAxis(h) / (m * m);
  J.block<6, 3>(4, 1) = -ParallelAxisJacobian(h) / m;
  for (int k = 0; k < 6; ++k) J(4 + k, kInertiaOfQuantity[k]) = 1.0;
  return J;
}

bool PayloadEstimatorOptions::IsValidFor(const RobotModel& model, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (link < -1 || link >= model.n_links())
    return fail("link: expected -1 (the last link) or an index in [0, " + std::to_string(model.n_links()) + "), got " +
                std::to_string(link));
  if (!(max_relative_sigma > 0.0) || !std::isfinite(max_relative_sigma))
    return fail("max_relative_sigma: expected a positive number, got " + std::to_string(max_relative_sigma));
  if (!(max_projection_distance > 0.0) || !std::isfinite(max_projection_distance))
    return fail("max_projection_distance: expected a positive number, got " + std::to_string(max_projection_distance));
  return true;
}

namespace {

// Step 1 of EstimatePayload, the equations A x = b on `link`: with two logs
// x = [β; φ] over both logs' rows (the unloaded first), with one log x = φ and
// b the loaded torques less the robot file's; names: β's (two logs), then φ's.
struct PayloadEquations {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  std::vector<std::string> names;
  Eigen::Index loaded_first = 0;  // first row of the loaded log
};

PayloadEquations StackPayloadEquations(const RobotModel& model, const TorqueLog& loaded, const TorqueLog* unloaded,
                                       const PayloadEstimatorOptions& options, int link) {
  PayloadEquations eq;
  if (unloaded) {
    const BaseParameters base = ComputeBaseParameters(model, options.friction, options.base);
    const int n_base = base.n_base();
    const Eigen::MatrixXd U =
        internal::StackLinkEquations(model, options.friction, &base, link, unloaded->motion,
                                     StackedTorques(model, *unloaded, false, "unloaded"), unloaded->parallel_filter,
                                     "unloaded");
    const Eigen::MatrixXd L =
        internal::StackLinkEquations(model, options.friction, &base, link, loaded.motion,
                                     StackedTorques(model, loaded, false, "loaded"), loaded.parallel_filter, "loaded");
    eq.loaded_first = U.rows();
    eq.A = Eigen::MatrixXd::Zero(U.rows() + L.rows(), n_base + kInertialParametersPerLink);
    eq.A.topLeftCorner(U.rows(), n_base) = U.leftCols(n_base);
    eq.A.bottomRows(L.rows()) = L.leftCols(n_base + kInertialParametersPerLink);
    eq.b.resize(eq.A.rows());
    eq.b << U.col(n_base + kInertialParametersPerLink), L.col(n_base + kInertialParametersPerLink);
    eq.names = base.names;
  } else {
    const Eigen::MatrixXd L = internal::StackLinkEquations(model, options.friction, nullptr, link, loaded.motion,
                                                           StackedTorques(model, loaded, true, "loaded"),
                                                           loaded.parallel_filter, "loaded");
    eq.A = L.leftCols(kInertialParametersPerLink);
    eq.b = L.col(kInertialParametersPerLink) - L.col(kInertialParametersPerLink + 1);
  }
  for (const std::string& name : PayloadInertialParameterNames()) eq.names.push_back("payload " + name);
  return eq;
}

// Step 3 of EstimatePayload: the quantities' identifiability. Each depends
// on the φ entries its row of ∂q/∂φ touches (at a point where no entry
// vanishes by chance); one whose entries the motion does not determine
// (out->parameter_identifiable, parameter_reason) is not identifiable.
void ClassifyPayloadQuantities(const std::vector<std::string>& parameter_reason, const std::string& link_name,
                               PayloadEstimate* out) {
  InertialParameters generic;
  generic << 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0;
  const Matrix10 structure = PayloadQuantityJacobian(generic);
  out->identifiable.assign(kInertialParametersPerLink, true);
  out->not_identifiable_reason.assign(kInertialParametersPerLink, "");
  for (int k = 0; k < kInertialParametersPerLink; ++k) {
    std::vector<std::string> missing, reasons;
    for (int i = 0; i < kInertialParametersPerLink; ++i) {
      if (structure(k, i) == 0.0 || out->parameter_identifiable[i]) continue;
      missing.push_back(PayloadInertialParameterNames()[i]);
      if (reasons.empty()) reasons.push_back(parameter_reason[i]);
    }
    if (missing.empty()) continue;
    out->identifiable[k] = false;
    out->not_identifiable_reason[k] = "depends on " + JoinNames(missing) + " of link '" + link_name +
                                      "', which the motion does not determine (" + reasons.front() + ")";
  }
}

// Step 5 of EstimatePayload: the verdict (out->status, out->message) on an
// estimate whose quantities, σ and projection are set.
void JudgePayload(const PayloadEstimatorOptions& options, const std::string& link_name, bool all_identifiable,
                  PayloadEstimate* out) {
  char text[512];
  if (!all_identifiable) {
    std::vector<std::string> missing;
    for (int k = 0; k < kInertialParametersPerLink; ++k) {
      if (!out->identifiable[k]) missing.push_back(PayloadQuantityNames()[k]);
    }
    out->status = PayloadStatus::kNotIdentifiable;
    out->message = "the motion does not determine the payload's " + JoinNames(missing) + " on link '" + link_name +
                   "' (" + out->not_identifiable_reason[static_cast<size_t>(std::find(out->identifiable.begin(),
                   out->identifiable.end(), false) - out->identifiable.begin())] +
                   "); record a motion that turns the payload about three axes and moves it against gravity";
  } else if (out->projection_distance > options.max_projection_distance) {
    std::snprintf(text, sizeof(text),
                  "the least-squares payload on link '%s' is not a physical body (smallest pseudo-inertia eigenvalue "
                  "%.3g), and the nearest body is %.3g sigma from it (at most %g): check the link, the robot file (a "
                  "single log subtracts its model; an unloaded log of the same motion cancels its errors) and the "
                  "torque signs",
                  link_name.c_str(), out->min_pseudo_inertia_eigenvalue, out->projection_distance,
                  options.max_projection_distance);
    out->status = PayloadStatus::kNotPhysical;
    out->message = text;
  } else if (const int worst = WorstRelativeSigma(out->body, out->sigma);
             !(out->body.mass > 0.0) ||
             !(out->sigma[worst] <= options.max_relative_sigma * PayloadQuantityScale(out->body, worst))) {
    std::snprintf(text, sizeof(text),
                  "the payload's %s on link '%s' is %.4g with sigma %.3g (at most %g of %.3g expected): the payload's "
                  "torques are too small against the noise (signal/noise %.3g) or the motion hardly turns it; record "
                  "a longer or richer motion",
                  PayloadQuantityNames()[worst].c_str(), link_name.c_str(), PayloadQuantities(out->body)[worst],
                  out->sigma[worst], options.max_relative_sigma, PayloadQuantityScale(out->body, worst),
                  out->payload_signal_to_noise);
    out->status = PayloadStatus::kPoorlyDetermined;
    out->message = text;
  }
}

}  // namespace

PayloadEstimate EstimatePayload(const RobotModel& model, const TorqueLog& loaded, const TorqueLog* unloaded,
                                const PayloadEstimatorOptions& options) {
  std::string why;
  if (!options.IsValidFor(model, &why)) throw std::invalid_argument("payload: " + why);
  PayloadEstimate out;
  out.two_logs = unloaded != nullptr;
  out.link = options.link < 0 ? model.n_links() - 1 : options.link;
  const std::string& link_name = model.links()[static_cast<size_t>(out.link)].name;

  // 1. The equations A x = b (StackPayloadEquations).
  const PayloadEquations equations = StackPayloadEquations(model, loaded, unloaded, options, out.link);
  const Eigen::MatrixXd& A = equations.A;
  const Eigen::VectorXd& b = equations.b;
  const std::vector<std::string>& names = equations.names;
  const Eigen::Index loaded_first = equations.loaded_first;
  const Eigen::Index p = A.cols(), first = p - kInertialParametersPerLink;
  out.n_equations = A.rows();
  if (out.n_equations <= p) {
    throw std::invalid_argument("payload: " + std::to_string(out.n_equations) + " equations for " + std::to_string(p) +
                                " unknowns; record longer logs");
  }

  // 2. Least squares, what it determines, and σ² = ‖e‖²/(m − rank).
  const internal::MinNormSolution solution = internal::SolveMinNorm(A, b, names);
  out.rank = solution.ls.rank;
  const double sigma2 = solution.residual2 / static_cast<double>(out.n_equations - out.rank);
  out.residual_rms = std::sqrt(solution.residual2 / static_cast<double>(out.n_equations));
  const Eigen::MatrixXd F = solution.pseudo_inverse_factor.bottomRows(kInertialParametersPerLink);
  const Matrix10 M = F * F.transpose();  // covariance / σ²
  out.parameter_identifiable.assign(kInertialParametersPerLink, false);
  std::vector<std::string> parameter_reason(kInertialParametersPerLink);
  InertialParameters phi_filled = solution.x.tail(kInertialParametersPerLink);  // every entry finite
  out.phi = phi_filled;
  const Eigen::VectorXd residual = A * solution.x - b;
  // σ from the residual as it is (residual_covariance.h): the sandwich with
  // G = (AᵀA)⁺ = F_all F_allᵀ over the two logs' samples, one after the other.
  const Eigen::MatrixXd G = solution.pseudo_inverse_factor * solution.pseudo_inverse_factor.transpose();
  const Eigen::MatrixXd sandwich =
      StackedSandwichCovariance(A, residual, model.n_dof(), G, sigma2, &out.covariance_method);
  out.covariance = sandwich.bottomRightCorner(kInertialParametersPerLink, kInertialParametersPerLink);
  out.covariance_white = sigma2 * M;
  bool all_identifiable = true;
  for (int i = 0; i < kInertialParametersPerLink; ++i) {
    out.parameter_identifiable[i] = solution.ls.identifiable[static_cast<size_t>(first + i)];
    parameter_reason[i] = solution.ls.reason[static_cast<size_t>(first + i)];
    if (out.parameter_identifiable[i]) continue;
    all_identifiable = false;
    out.phi[i] = kNaN;
    for (Matrix10* c : {&out.covariance, &out.covariance_white}) {
      c->row(i).setConstant(kNaN);
      c->col(i).setConstant(kNaN);
    }
  }
  const Eigen::VectorXd payload_torque = A.bottomRows(A.rows() - loaded_first).rightCols(kInertialParametersPerLink) * phi_filled;
  out.payload_signal_to_noise = payload_torque.norm() / residual.tail(A.rows() - loaded_first).norm();

  // 3. The quantities' identifiability.
  ClassifyPayloadQuantities(parameter_reason, link_name, &out);

  // 4. The physically consistent estimate and the quantities' σ at it.
  out.min_pseudo_inertia_eigenvalue = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(PseudoInertia(phi_filled))
                                          .eigenvalues()
                                          .minCoeff();
  if (all_identifiable) {
    // The nearest body in the metric of the covariance (Mahalanobis), the
    // white one's shape when the batch-means covariance is not definite.
    double distance2 = 0.0;
    const bool definite = Eigen::LLT<Matrix10>(out.covariance).info() == Eigen::Success;
    const Matrix10 metric = definite ? Matrix10(out.covariance / sigma2) : M;
    out.consistent_phi = ProjectOntoConsistent(phi_filled, metric, &distance2);
    out.projection_distance = distance2 > 0.0 ? std::sqrt(distance2 / sigma2) : 0.0;
    out.body = PayloadBodyFromParameters(out.consistent_phi);
    const Matrix10 J = PayloadQuantityJacobian(out.consistent_phi);
    out.sigma = (J * out.covariance * J.transpose()).diagonal().cwiseSqrt();
    out.sigma_white = (J * out.covariance_white * J.transpose()).diagonal().cwiseSqrt();
  } else {
    out.consistent_phi.setConstant(kNaN);
    out.body = PayloadBodyFromParameters(phi_filled);
    const Matrix10 J = PayloadQuantityJacobian(phi_filled);
    out.sigma = (J * sandwich.bottomRightCorner(kInertialParametersPerLink, kInertialParametersPerLink) *
                 J.transpose()).diagonal().cwiseSqrt();
    out.sigma_white = (J * (sigma2 * M) * J.transpose()).diagonal().cwiseSqrt();
    Vector10 q = PayloadQuantities(out.body);
    for (int k = 0; k < kInertialParametersPerLink; ++k) {
      if (out.identifiable[k]) continue;
      q[k] = kNaN;
      out.sigma[k] = out.sigma_white[k] = kNaN;
    }
    out.body.mass = q[0];
    out.body.p_BoPcm_B = q.segment<3>(1);
    out.body.I_Pcm_B = q.tail<6>();
  }

  // 5. The verdict.
  JudgePayload(options, link_name, all_identifiable, &out);
  return out;
}

}  // namespace idbench
