#include "idbench/ident/physically_consistent.h"

#include <nlopt.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

constexpr int kP = kInertialParametersPerLink;

// Entry (row, column) of U/e^α that θ_k sets, k = 1…9; θ_0 = α scales U.
// Order (α, d1, d2, d3, s12, s23, s13, t1, t2, t3).
constexpr int kRow[kP] = {-1, 0, 1, 2, 0, 1, 0, 0, 1, 2};
constexpr int kCol[kP] = {-1, 0, 1, 2, 1, 2, 2, 3, 3, 3};

std::string Size(Eigen::Index n) { return std::to_string(n); }

// π of a symmetric J; linear in J.
InertialParameters ParametersOfSymmetric(const Eigen::Matrix4d& J) {
  const double trace_sigma = J(0, 0) + J(1, 1) + J(2, 2);
  InertialParameters pi;
  pi << J(3, 3), J(0, 3), J(1, 3), J(2, 3),  //
      trace_sigma - J(0, 0), -J(0, 1), trace_sigma - J(1, 1), -J(0, 2), -J(1, 2), trace_sigma - J(2, 2);
  return pi;
}

// NLopt's view of the objective, with the best point seen (L-BFGS may end
// on a failed line search away from it).
struct NloptContext {
  PhysicallyConsistentObjective* objective = nullptr;
  Eigen::VectorXd gradient;
  Eigen::VectorXd best_x;
  double best_f = std::numeric_limits<double>::infinity();
  int evaluations = 0;
};

double NloptObjective(unsigned n, const double* x, double* grad, void* data) {
  auto* context = static_cast<NloptContext*>(data);
  const Eigen::Map<const Eigen::VectorXd> x_map(x, n);
  ++context->evaluations;
  double f = context->objective->Evaluate(x_map, grad ? &context->gradient : nullptr);
  if (!std::isfinite(f)) {
    // exp overflow far from the data: a wall the line search backs off from.
    f = HUGE_VAL;
    if (grad) context->gradient.setZero();
  }
  if (grad) Eigen::Map<Eigen::VectorXd>(grad, n) = context->gradient;
  if (f < context->best_f) {
    context->best_f = f;
    context->best_x = x_map;
  }
  return f;
}

}  // namespace

Eigen::Matrix4d PseudoInertia(const Eigen::Ref<const Eigen::VectorXd>& pi10) {
  if (pi10.size() != kP) {
    throw std::invalid_argument("PseudoInertia: expected 10 parameters, got " + Size(pi10.size()));
  }
  const double m = pi10[0], ixx = pi10[4], ixy = pi10[5], iyy = pi10[6], ixz = pi10[7], iyz = pi10[8],
               izz = pi10[9];
  const double half_trace = 0.5 * (ixx + iyy + izz);
  Eigen::Matrix4d J;
  J << half_trace - ixx, -ixy, -ixz, pi10[1],  //
      -ixy, half_trace - iyy, -iyz, pi10[2],   //
      -ixz, -iyz, half_trace - izz, pi10[3],   //
      pi10[1], pi10[2], pi10[3], m;
  return J;
}

InertialParameters InertialParametersFromPseudoInertia(const Eigen::Matrix4d& J) {
  return ParametersOfSymmetric(0.5 * (J + J.transpose()));
}

InertialParameters InertialParametersFromLogCholesky(const Eigen::Ref<const Eigen::VectorXd>& theta,
                                                     Eigen::Matrix<double, 10, 10>* d_pi_d_theta) {
  if (theta.size() != kP) {
    throw std::invalid_argument("InertialParametersFromLogCholesky: expected 10 coordinates, got " +
                                Size(theta.size()));
  }
  // V = U/e^α: exponentials on the diagonal, 1 in the corner.
  Eigen::Matrix4d V = Eigen::Matrix4d::Zero();
  V(3, 3) = 1.0;
  for (int k = 1; k < kP; ++k) V(kRow[k], kCol[k]) = k <= 3 ? std::exp(theta[k]) : theta[k];
  const double e2a = std::exp(2.0 * theta[0]);
  const Eigen::Matrix4d J = e2a * V * V.transpose();
  const InertialParameters pi = ParametersOfSymmetric(J);
  if (d_pi_d_theta) {
    // ∂J/∂α = 2 J. For the entry V_ij that θ_k sets, ∂J/∂θ_k = e^{2α} (E V ᵀ + V Eᵀ) ∂V_ij/∂θ_k
    // with E the unit matrix at (i, j): row i of E Vᵀ is column j of V.
    d_pi_d_theta->col(0) = 2.0 * pi;
    for (int k = 1; k < kP; ++k) {
      const int i = kRow[k], j = kCol[k];
      const double dv = k <= 3 ? V(i, i) : 1.0;
      Eigen::Matrix4d dJ = Eigen::Matrix4d::Zero();
      dJ.row(i) = (e2a * dv) * V.col(j).transpose();
      dJ += dJ.transpose().eval();
      d_pi_d_theta->col(k) = ParametersOfSymmetric(dJ);
    }
  }
  return pi;
}

LogCholeskyParameters LogCholeskyFromPseudoInertia(const Eigen::Matrix4d& J) {
  const Eigen::Matrix4d J_sym = 0.5 * (J + J.transpose());
  // Upper-triangular U with J = U Uᵀ: with P the reversal permutation,
  // P J P = L Lᵀ gives U = P L P.
  const Eigen::LLT<Eigen::Matrix4d> llt(J_sym.reverse());
  if (!J_sym.allFinite() || llt.info() != Eigen::Success) {
    throw std::invalid_argument("LogCholeskyFromPseudoInertia: expected a positive definite pseudo-inertia");
  }
  const Eigen::Matrix4d L = llt.matrixL();
  const Eigen::Matrix4d U = L.reverse();
  if (!(U.diagonal().array() > 0.0).all()) {
    throw std::invalid_argument("LogCholeskyFromPseudoInertia: expected a positive definite pseudo-inertia");
  }
  const Eigen::Matrix4d V = U / U(3, 3);
  LogCholeskyParameters theta;
  theta[0] = std::log(U(3, 3));
  for (int k = 1; k < kP; ++k) {
    const double v = V(kRow[k], kCol[k]);
    theta[k] = k <= 3 ? std::log(v) : v;
  }
  return theta;
}

Eigen::VectorXd MinPseudoInertiaEigenvalues(const Eigen::VectorXd& pi, int n_links) {
  if (n_links < 0 || pi.size() < kP * n_links) {
    throw std::invalid_argument("MinPseudoInertiaEigenvalues: expected at least " + Size(kP * n_links) +
                                " parameters, got " + Size(pi.size()));
  }
  Eigen::VectorXd min_eigenvalue(n_links);
  for (int l = 0; l < n_links; ++l) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(PseudoInertia(pi.segment<kP>(kP * l)),
                                                             Eigen::EigenvaluesOnly);
    min_eigenvalue[l] = eig.eigenvalues()[0];
  }
  return min_eigenvalue;
}

Eigen::VectorXd ClosestStandardParameters(const BaseParameters& base, const Eigen::VectorXd& beta,
                                          const Eigen::VectorXd& pi_prior) {
  const Eigen::MatrixXd& C = base.combination;
  if (beta.size() != C.rows() || pi_prior.size() != C.cols()) {
    throw std::invalid_argument("ClosestStandardParameters: expected beta of " + Size(C.rows()) +
                                " and pi_prior of " + Size(C.cols()) + " entries, got " + Size(beta.size()) +
                                " and " + Size(pi_prior.size()));
  }
  // The minimum-norm δ with C δ = β − C π_prior is C⁺ (β − C π_prior).
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(C);
  return pi_prior + cod.solve(beta - C * pi_prior);
}

bool PhysicallyConsistentOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (max_evaluations < 1) return fail("max_evaluations must be >= 1, got " + std::to_string(max_evaluations));
  if (!(relative_tolerance >= 0.0) || !std::isfinite(relative_tolerance)) {
    return fail("relative_tolerance must be finite and >= 0, got " + std::to_string(relative_tolerance));
  }
  if (!(eigenvalue_floor > 0.0 && eigenvalue_floor < 1.0)) {
    return fail("eigenvalue_floor must be in (0, 1), got " + std::to_string(eigenvalue_floor));
  }
  return true;
}

PhysicallyConsistentObjective::PhysicallyConsistentObjective(const Eigen::MatrixXd& W_base,
                                                             const Eigen::VectorXd& tau,
                                                             const BaseParameters& base, int n_links)
    : n_links_(n_links) {
  const Eigen::MatrixXd& C = base.combination;
  const Eigen::Index n_base = base.n_base();
  if (W_base.cols() != n_base || C.rows() != n_base) {
    throw std::invalid_argument("physically consistent fit: expected W_base with " + Size(n_base) +
                                " columns (the base parameters), got " + Size(W_base.cols()));
  }
  if (W_base.rows() != tau.size() || W_base.rows() < n_base) {
    throw std::invalid_argument("physically consistent fit: expected tau of W_base's " + Size(W_base.rows()) +
                                " rows, at least " + Size(n_base) + ", got " + Size(tau.size()));
  }
  if (n_links < 0 || C.cols() < kP * n_links) {
    throw std::invalid_argument("physically consistent fit: expected at least " + Size(kP * n_links) +
                                " standard parameters for " + std::to_string(n_links) + " links, got " +
                                Size(C.cols()));
  }
  if (!W_base.allFinite() || !tau.allFinite()) {
    throw std::invalid_argument("physically consistent fit: W_base and tau must be finite");
  }
  // Thin QR once: ‖W_b β − τ‖² = ‖R β − Q₁ᵀ τ‖² + ‖Q₂ᵀ τ‖² for every β.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(W_base);
  const Eigen::VectorXd q_tau = qr.householderQ().adjoint() * tau;
  const Eigen::MatrixXd R = qr.matrixQR().topRows(n_base).triangularView<Eigen::Upper>();
  A_ = R * C;
  b_ = q_tau.head(n_base);
  residual_floor_ = q_tau.tail(W_base.rows() - n_base).squaredNorm();
  pi_.resize(C.cols());
  r_.resize(n_base);
  g_pi_.resize(C.cols());
  jacobians_.resize(kP, kP * n_links);
}

Eigen::VectorXd PhysicallyConsistentObjective::StandardParametersAt(const Eigen::VectorXd& x) const {
  if (x.size() != n_variables()) {
    throw std::invalid_argument("physically consistent fit: expected " + Size(n_variables()) +
                                " variables, got " + Size(x.size()));
  }
  Eigen::VectorXd pi = x;
  for (int l = 0; l < n_links_; ++l) {
    pi.segment<kP>(kP * l) = InertialParametersFromLogCholesky(x.segment<kP>(kP * l));
  }
  return pi;
}

Eigen::VectorXd PhysicallyConsistentObjective::VariablesAt(const Eigen::VectorXd& pi) const {
  if (pi.size() != n_variables()) {
    throw std::invalid_argument("physically consistent fit: expected " + Size(n_variables()) +
                                " standard parameters, got " + Size(pi.size()));
  }
  Eigen::VectorXd x = pi;
  for (int l = 0; l < n_links_; ++l) {
    x.segment<kP>(kP * l) = LogCholeskyFromPseudoInertia(PseudoInertia(pi.segment<kP>(kP * l)));
  }
  return x;
}

double PhysicallyConsistentObjective::Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                               Eigen::VectorXd* gradient) {
  if (x.size() != n_variables()) {
    throw std::invalid_argument("physically consistent fit: expected " + Size(n_variables()) +
                                " variables, got " + Size(x.size()));
  }
  const Eigen::Index n_friction = n_variables() - kP * n_links_;
  // π(x): link blocks through log-Cholesky, friction as is.
  if (gradient) gradient->resize(n_variables());
  for (int l = 0; l < n_links_; ++l) {
    Eigen::Matrix<double, kP, kP> d_pi_d_theta;
    pi_.segment<kP>(kP * l) =
        InertialParametersFromLogCholesky(x.segment<kP>(kP * l), gradient ? &d_pi_d_theta : nullptr);
    if (gradient) jacobians_.middleCols<kP>(kP * l) = d_pi_d_theta;
  }
  pi_.tail(n_friction) = x.tail(n_friction);
  // Residual in the QR coordinates.
  r_.noalias() = A_ * pi_;
  r_ -= b_;
  const double f = r_.squaredNorm() + residual_floor_;
  if (gradient) {
    // ∇_π f = 2 Aᵀ r, then the chain rule per link.
    g_pi_.noalias() = A_.transpose() * r_;
    g_pi_ *= 2.0;
    for (int l = 0; l < n_links_; ++l) {
      gradient->segment<kP>(kP * l).noalias() =
          jacobians_.middleCols<kP>(kP * l).transpose() * g_pi_.segment<kP>(kP * l);
    }
    gradient->tail(n_friction) = g_pi_.tail(n_friction);
  }
  return f;
}

PhysicallyConsistentFit SolvePhysicallyConsistent(const Eigen::MatrixXd& W_base, const Eigen::VectorXd& tau,
                                                  const BaseParameters& base, int n_links,
                                                  const Eigen::VectorXd& beta_ols, const Eigen::VectorXd& pi_prior,
                                                  const PhysicallyConsistentOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("physically consistent options: " + why);
  PhysicallyConsistentObjective objective(W_base, tau, base, n_links);
  if (!beta_ols.allFinite() || !pi_prior.allFinite()) {
    throw std::invalid_argument("physically consistent fit: beta_ols and pi_prior must be finite");
  }
  PhysicallyConsistentFit fit;
  fit.ols_cost = (W_base * beta_ols - tau).squaredNorm();

  // Start: the parameters nearest the prior that reproduce β_ols, each link's
  // J with its eigenvalues floored (a link without a positive eigenvalue is
  // floored against the largest eigenvalue of all links).
  Eigen::VectorXd pi0 = ClosestStandardParameters(base, beta_ols, pi_prior);
  std::vector<Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>> eig(static_cast<size_t>(n_links));
  double largest = 0.0;
  for (int l = 0; l < n_links; ++l) {
    eig[static_cast<size_t>(l)].compute(PseudoInertia(pi0.segment<kP>(kP * l)));
    largest = std::max(largest, eig[static_cast<size_t>(l)].eigenvalues()[3]);
  }
  if (!(largest > 0.0)) largest = 1.0;
  for (int l = 0; l < n_links; ++l) {
    const auto& e = eig[static_cast<size_t>(l)];
    const double reference = e.eigenvalues()[3] > 0.0 ? e.eigenvalues()[3] : largest;
    const Eigen::Vector4d lambda = e.eigenvalues().cwiseMax(options.eigenvalue_floor * reference);
    const Eigen::Matrix4d J = e.eigenvectors() * lambda.asDiagonal() * e.eigenvectors().transpose();
    pi0.segment<kP>(kP * l) = InertialParametersFromPseudoInertia(J);
  }
  Eigen::VectorXd x = objective.VariablesAt(pi0);
  fit.start_cost = objective.Evaluate(x);

  // Minimise with L-BFGS; keep the best point seen.
  NloptContext context;
  context.objective = &objective;
  context.best_x = x;
  context.best_f = fit.start_cost;
  nlopt_opt opt = nlopt_create(NLOPT_LD_LBFGS, static_cast<unsigned>(x.size()));
  nlopt_set_min_objective(opt, &NloptObjective, &context);
  nlopt_set_ftol_rel(opt, options.relative_tolerance);
  nlopt_set_maxeval(opt, options.max_evaluations);
  double f_final = 0.0;
  const nlopt_result result = x.size() > 0 ? nlopt_optimize(opt, x.data(), &f_final) : NLOPT_SUCCESS;
  nlopt_destroy(opt);

  // Report in standard parameters.
  fit.pi = objective.StandardParametersAt(context.best_x);
  fit.beta = base.combination * fit.pi;
  fit.cost = (W_base * fit.beta - tau).squaredNorm();
  fit.min_pseudo_inertia_eigenvalue = MinPseudoInertiaEigenvalues(fit.pi, n_links);
  fit.evaluations = context.evaluations;
  fit.status = nlopt_result_to_string(result);
  fit.converged = result == NLOPT_SUCCESS || result == NLOPT_FTOL_REACHED || result == NLOPT_XTOL_REACHED ||
                  result == NLOPT_STOPVAL_REACHED;
  return fit;
}

}  // namespace idbench
