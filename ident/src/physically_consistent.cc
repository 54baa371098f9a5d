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

// Entry (row, column) of U that coordinate k sets, in the order
// (α|u44, d1|u11, d2|u22, d3|u33, s12, s23, s13, t1, t2, t3).
constexpr int kRow[kP] = {3, 0, 1, 2, 0, 1, 0, 0, 1, 2};
constexpr int kCol[kP] = {3, 0, 1, 2, 1, 2, 2, 3, 3, 3};

// Levenberg–Marquardt damping of the preconditioner, relative to the
// Gauss–Newton diagonal, and its floor relative to the largest diagonal entry:
// keeps L well defined where the data do not reach (unidentifiable
// directions) without changing the scaling elsewhere.
constexpr double kPreconditionerDamping = 1e-6;
constexpr double kPreconditionerFloor = 1e-12;

std::string Size(Eigen::Index n) { return std::to_string(n); }

// ‖W_b β − τ‖² = ‖R β − z‖² + ρ² from the factor [R z; 0 ρ] of [W_b τ].
double Cost(const Eigen::MatrixXd& factor, const Eigen::VectorXd& beta) {
  const Eigen::Index p = beta.size();
  const double rho = factor(p, p);
  return (factor.topLeftCorner(p, p).triangularView<Eigen::Upper>() * beta - factor.col(p).head(p)).squaredNorm() +
         rho * rho;
}

void CheckVariables(Eigen::Index got, Eigen::Index expected) {
  if (got != expected) {
    throw std::invalid_argument("physically consistent fit: expected " + Size(expected) + " variables, got " +
                                Size(got));
  }
}

// π of a symmetric J; linear in J.
InertialParameters ParametersOfSymmetric(const Eigen::Matrix4d& J) {
  const double trace_sigma = J(0, 0) + J(1, 1) + J(2, 2);
  InertialParameters pi;
  pi << J(3, 3), J(0, 3), J(1, 3), J(2, 3),  //
      trace_sigma - J(0, 0), -J(0, 1), trace_sigma - J(1, 1), -J(0, 2), -J(1, 2), trace_sigma - J(2, 2);
  return pi;
}

// NLopt's view of the objective: φ(z) = f(x_b + T z)/scale, and the best
// point seen (a line search may end away from it).
struct NloptContext {
  PhysicallyConsistentObjective* objective = nullptr;
  Eigen::VectorXd x_base;          // x at z = 0
  Eigen::MatrixXd T;               // x = x_base + T z (n × n)
  double scale = 1.0;              // [N² m²]
  Eigen::VectorXd x, gradient_x;   // workspace
  Eigen::VectorXd best_x;
  double best_f = std::numeric_limits<double>::infinity();
  int evaluations = 0;
};

double NloptObjective(unsigned n, const double* z, double* grad, void* data) {
  auto* context = static_cast<NloptContext*>(data);
  const Eigen::Map<const Eigen::VectorXd> z_map(z, n);
  context->x = context->x_base;
  context->x.noalias() += context->T * z_map;
  ++context->evaluations;
  double f = context->objective->Evaluate(context->x, grad ? &context->gradient_x : nullptr);
  if (!std::isfinite(f)) {
    // Overflow far from the data: a wall the line search backs off from.
    f = HUGE_VAL;
    if (grad) context->gradient_x.setZero();
  }
  if (grad) {
    Eigen::Map<Eigen::VectorXd> grad_z(grad, n);
    grad_z.noalias() = context->T.transpose() * context->gradient_x;
    grad_z /= context->scale;
  }
  if (f < context->best_f) {
    context->best_f = f;
    context->best_x = context->x;
  }
  return f / context->scale;
}

// Centres the next round on the best point: x_b = best x, scale = best f, and
// T = L⁻ᵀ with L Lᵀ = M ≈ ∇²φ(x_b), the damped Gauss–Newton curvature
// 2 (∂r/∂x)ᵀ ∂r/∂x / scale, so that ∇²φ ≈ 𝟙 in z at the start of the round.
void CenterRound(NloptContext* context) {
  const Eigen::Index n = context->best_x.size();
  context->x_base = context->best_x;
  context->scale = context->best_f;
  const Eigen::MatrixXd Jr = context->objective->ResidualJacobian(context->x_base);
  Eigen::MatrixXd M = Jr.transpose() * Jr;
  const Eigen::VectorXd d = M.diagonal();
  const double floor = kPreconditionerFloor * std::max(d.maxCoeff(), std::numeric_limits<double>::min());
  M.diagonal() += kPreconditionerDamping * d + Eigen::VectorXd::Constant(n, floor);
  M *= 2.0 / context->scale;
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  context->T = Eigen::MatrixXd::Identity(n, n);
  if (llt.info() == Eigen::Success) llt.matrixU().solveInPlace(context->T);
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

InertialParameters InertialParametersFromFactor(InertiaParameterization parameterization,
                                                const Eigen::Ref<const Eigen::VectorXd>& coordinates,
                                                FactorJacobian* jacobian) {
  if (coordinates.size() != kP) {
    throw std::invalid_argument("InertialParametersFromFactor: expected 10 coordinates, got " +
                                Size(coordinates.size()));
  }
  const bool log = parameterization == InertiaParameterization::kLogCholesky;
  // U, and ∂U_ij/∂coordinate_k for the entry (i, j) that coordinate k sets.
  // Log-Cholesky: U = e^α V with V_33 = 1, V_ii = e^{d_i}, the rest as is.
  Eigen::Matrix4d U = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, kP, 1> dU;
  const double e_alpha = log ? std::exp(coordinates[0]) : 1.0;
  for (int k = 0; k < kP; ++k) {
    double v = coordinates[k], dv = 1.0;  // V_ij and ∂V_ij/∂c_k
    if (log && k == 0) v = 1.0;
    if (log && k >= 1 && k <= 3) v = dv = std::exp(coordinates[k]);
    U(kRow[k], kCol[k]) = e_alpha * v;
    dU[k] = e_alpha * dv;  // (∂U/∂α is handled on its own below)
  }
  const InertialParameters pi = ParametersOfSymmetric(U * U.transpose());
  if (jacobian) {
    // ∂J/∂c_k = ∂U/∂c_k Uᵀ + U ∂Uᵀ/∂c_k; for a single entry (i, j), row i of
    // the first term is ∂U_ij/∂c_k · (column j of U)ᵀ. For α, ∂J/∂α = 2 J.
    for (int k = 0; k < kP; ++k) {
      if (log && k == 0) {
        jacobian->col(0) = 2.0 * pi;
        continue;
      }
      Eigen::Matrix4d dJ = Eigen::Matrix4d::Zero();
      dJ.row(kRow[k]) = dU[k] * U.col(kCol[k]).transpose();
      dJ += dJ.transpose().eval();
      jacobian->col(k) = ParametersOfSymmetric(dJ);
    }
  }
  return pi;
}

PseudoInertiaFactor FactorFromPseudoInertia(InertiaParameterization parameterization, const Eigen::Matrix4d& J) {
  const Eigen::Matrix4d J_sym = 0.5 * (J + J.transpose());
  // Upper-triangular U with J = U Uᵀ: with P the reversal permutation,
  // P J P = L Lᵀ gives U = P L P.
  const Eigen::LLT<Eigen::Matrix4d> llt(J_sym.reverse());
  const Eigen::Matrix4d U = Eigen::Matrix4d(llt.matrixL()).reverse();
  if (!J_sym.allFinite() || llt.info() != Eigen::Success || !(U.diagonal().array() > 0.0).all()) {
    throw std::invalid_argument("FactorFromPseudoInertia: expected a positive definite pseudo-inertia");
  }
  PseudoInertiaFactor coordinates;
  for (int k = 0; k < kP; ++k) coordinates[k] = U(kRow[k], kCol[k]);
  if (parameterization == InertiaParameterization::kLogCholesky) {
    const double e_alpha = U(3, 3);
    coordinates /= e_alpha;
    coordinates[0] = std::log(e_alpha);
    for (int k = 1; k <= 3; ++k) coordinates[k] = std::log(coordinates[k]);
  }
  return coordinates;
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
  if (!(relative_tolerance >= 0.0 && relative_tolerance < 1.0)) {
    return fail("relative_tolerance must be in [0, 1), got " + std::to_string(relative_tolerance));
  }
  if (!(eigenvalue_floor > 0.0 && eigenvalue_floor < 1.0)) {
    return fail("eigenvalue_floor must be in (0, 1), got " + std::to_string(eigenvalue_floor));
  }
  if (!(pseudo_inertia_margin >= 0.0 && pseudo_inertia_margin <= 0.5 * eigenvalue_floor)) {
    return fail("pseudo_inertia_margin must be in [0, eigenvalue_floor/2], got " +
                std::to_string(pseudo_inertia_margin));
  }
  return true;
}

PhysicallyConsistentObjective::PhysicallyConsistentObjective(const Eigen::MatrixXd& factor,
                                                             const BaseParameters& base, int n_links,
                                                             InertiaParameterization parameterization,
                                                             const std::vector<Eigen::Matrix4d>& margins,
                                                             const std::vector<int>& nonnegative)
    : n_links_(n_links), parameterization_(parameterization), squared_(nonnegative) {
  const Eigen::MatrixXd& C = base.combination;
  const Eigen::Index n_base = base.n_base();
  if (factor.rows() != n_base + 1 || factor.cols() != n_base + 1 || C.rows() != n_base) {
    throw std::invalid_argument("physically consistent fit: expected the " + Size(n_base + 1) + " × " +
                                Size(n_base + 1) + " factor of [W_base tau] (the base parameters and tau), got " +
                                Size(factor.rows()) + " × " + Size(factor.cols()));
  }
  if (n_links < 0 || C.cols() < kP * n_links) {
    throw std::invalid_argument("physically consistent fit: expected at least " + Size(kP * n_links) +
                                " standard parameters for " + std::to_string(n_links) + " links, got " +
                                Size(C.cols()));
  }
  if (!factor.allFinite()) {
    throw std::invalid_argument("physically consistent fit: expected a finite factor of [W_base tau]");
  }
  if (!margins.empty() && margins.size() != static_cast<size_t>(n_links)) {
    throw std::invalid_argument("physically consistent fit: expected " + std::to_string(n_links) +
                                " margins, got " + std::to_string(margins.size()));
  }
  for (int k : nonnegative) {
    if (k < kP * n_links || k >= C.cols()) {
      throw std::invalid_argument("physically consistent fit: expected nonnegative indices of friction entries in [" +
                                  Size(kP * n_links) + ", " + Size(C.cols()) + "), got " + std::to_string(k));
    }
  }
  std::sort(squared_.begin(), squared_.end());
  squared_.erase(std::unique(squared_.begin(), squared_.end()), squared_.end());
  pi_margin_ = Eigen::VectorXd::Zero(C.cols());
  for (size_t l = 0; l < margins.size(); ++l) {
    pi_margin_.segment<kP>(kP * static_cast<Eigen::Index>(l)) = InertialParametersFromPseudoInertia(margins[l]);
  }
  // ‖W_b β − τ‖² = ‖R β − z‖² + ρ² for every β.
  const Eigen::MatrixXd R = factor.topLeftCorner(n_base, n_base).triangularView<Eigen::Upper>();
  A_ = R * C;
  b_ = factor.col(n_base).head(n_base);
  residual_floor_ = factor(n_base, n_base) * factor(n_base, n_base);
  pi_.resize(C.cols());
  r_.resize(n_base);
  g_pi_.resize(C.cols());
  jacobians_.resize(kP, kP * n_links);
}

Eigen::VectorXd PhysicallyConsistentObjective::StandardParametersAt(const Eigen::VectorXd& x) const {
  CheckVariables(x.size(), n_variables());
  Eigen::VectorXd pi = x;
  for (int l = 0; l < n_links_; ++l) {
    pi.segment<kP>(kP * l) =
        pi_margin_.segment<kP>(kP * l) + InertialParametersFromFactor(parameterization_, x.segment<kP>(kP * l));
  }
  for (int k : squared_) pi[k] = x[k] * x[k];
  return pi;
}

Eigen::VectorXd PhysicallyConsistentObjective::VariablesAt(const Eigen::VectorXd& pi) const {
  CheckVariables(pi.size(), n_variables());
  Eigen::VectorXd x = pi;
  for (int l = 0; l < n_links_; ++l) {
    x.segment<kP>(kP * l) = FactorFromPseudoInertia(
        parameterization_, PseudoInertia(pi.segment<kP>(kP * l) - pi_margin_.segment<kP>(kP * l)));
  }
  for (int k : squared_) {
    if (!(pi[k] >= 0.0)) {
      throw std::invalid_argument("physically consistent fit: expected entry " + std::to_string(k) +
                                  " >= 0, got " + std::to_string(pi[k]));
    }
    x[k] = std::sqrt(pi[k]);
  }
  return x;
}

double PhysicallyConsistentObjective::Evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                               Eigen::VectorXd* gradient) {
  CheckVariables(x.size(), n_variables());
  const Eigen::Index n_friction = n_variables() - kP * n_links_;
  // π(x): link blocks through the factor plus the margin, friction as is.
  for (int l = 0; l < n_links_; ++l) {
    FactorJacobian d_pi_d_x;
    pi_.segment<kP>(kP * l) =
        InertialParametersFromFactor(parameterization_, x.segment<kP>(kP * l), gradient ? &d_pi_d_x : nullptr);
    pi_.segment<kP>(kP * l) += pi_margin_.segment<kP>(kP * l);
    if (gradient) jacobians_.middleCols<kP>(kP * l) = d_pi_d_x;
  }
  pi_.tail(n_friction) = x.tail(n_friction);
  for (int k : squared_) pi_[k] = x[k] * x[k];
  // Residual in the QR coordinates.
  r_.noalias() = A_ * pi_;
  r_ -= b_;
  const double f = r_.squaredNorm() + residual_floor_;
  if (gradient) {
    // ∇_π f = 2 Aᵀ r, then the chain rule per link.
    gradient->resize(n_variables());
    g_pi_.noalias() = A_.transpose() * r_;
    g_pi_ *= 2.0;
    for (int l = 0; l < n_links_; ++l) {
      gradient->segment<kP>(kP * l).noalias() =
          jacobians_.middleCols<kP>(kP * l).transpose() * g_pi_.segment<kP>(kP * l);
    }
    gradient->tail(n_friction) = g_pi_.tail(n_friction);
    for (int k : squared_) (*gradient)[k] *= 2.0 * x[k];
  }
  return f;
}

Eigen::VectorXd PhysicallyConsistentObjective::Residual(const Eigen::VectorXd& x) const {
  return A_ * StandardParametersAt(x) - b_;
}

Eigen::MatrixXd PhysicallyConsistentObjective::ResidualJacobian(const Eigen::VectorXd& x) const {
  CheckVariables(x.size(), n_variables());
  Eigen::MatrixXd J = A_;
  for (int l = 0; l < n_links_; ++l) {
    FactorJacobian d_pi_d_x;
    InertialParametersFromFactor(parameterization_, x.segment<kP>(kP * l), &d_pi_d_x);
    J.middleCols<kP>(kP * l) = A_.middleCols<kP>(kP * l) * d_pi_d_x;
  }
  for (int k : squared_) J.col(k) *= 2.0 * x[k];
  return J;
}

PhysicallyConsistentFit SolvePhysicallyConsistent(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                                  const Eigen::VectorXd& beta_ols, const Eigen::VectorXd& pi_prior,
                                                  const PhysicallyConsistentOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("physically consistent options: " + why);
  if (!beta_ols.allFinite() || !pi_prior.allFinite()) {
    throw std::invalid_argument("physically consistent fit: expected finite beta_ols and pi_prior");
  }
  PhysicallyConsistentFit fit;
  Eigen::VectorXd pi0 = ClosestStandardParameters(base, beta_ols, pi_prior);
  if (n_links < 0 || pi0.size() < kP * n_links) {
    throw std::invalid_argument("physically consistent fit: expected at least " + Size(kP * n_links) +
                                " standard parameters for " + std::to_string(n_links) + " links, got " +
                                Size(pi0.size()));
  }

  // Start: each link's J with its eigenvalues floored against its largest (a
  // link without a positive eigenvalue against the largest of all links);
  // the margin M = margin · diag(J₀) ⪯ ½ J₀ then leaves J₀ − M ≻ 0.
  std::vector<Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>> eig(static_cast<size_t>(n_links));
  std::vector<Eigen::Matrix4d> margins(static_cast<size_t>(n_links));
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
    margins[static_cast<size_t>(l)] = options.pseudo_inertia_margin * Eigen::Matrix4d(J.diagonal().asDiagonal());
  }
  // A nonnegative entry starts positive: v = 0 is a stationary point of v².
  for (int k : options.nonnegative) {
    if (k >= 0 && k < pi0.size()) {
      const double small = options.eigenvalue_floor * std::max({1.0, std::abs(pi0[k]), std::abs(pi_prior[k])});
      pi0[k] = std::max(pi0[k], small);
    }
  }
  PhysicallyConsistentObjective objective(factor, base, n_links, options.parameterization, margins,
                                          options.nonnegative);
  fit.ols_cost = Cost(factor, beta_ols);
  NloptContext context;
  context.objective = &objective;
  context.best_x = objective.VariablesAt(pi0);
  context.best_f = objective.Evaluate(context.best_x);
  fit.start_cost = context.best_f;

  // Rounds of SLSQP, each preconditioned at the best point so far, while a
  // round lowers the cost by more than the tolerance. No f is below the
  // residual floor, so reaching it (up to the tolerance) ends the search.
  const Eigen::Index n = context.best_x.size();
  const double stop_value = objective.residual_floor() * (1.0 + options.relative_tolerance);
  nlopt_result result = NLOPT_SUCCESS;
  while (n > 0 && context.evaluations < options.max_evaluations && context.best_f > stop_value) {
    const double f_before = context.best_f;
    CenterRound(&context);
    nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, static_cast<unsigned>(n));
    if (!opt) {
      result = NLOPT_OUT_OF_MEMORY;
      break;
    }
    nlopt_set_min_objective(opt, &NloptObjective, &context);
    nlopt_set_ftol_rel(opt, options.relative_tolerance);
    nlopt_set_stopval(opt, stop_value / context.scale);
    nlopt_set_maxeval(opt, options.max_evaluations - context.evaluations);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    double phi = 0.0;
    result = nlopt_optimize(opt, z.data(), &phi);
    nlopt_destroy(opt);
    ++fit.rounds;
    if (f_before - context.best_f <= options.relative_tolerance * f_before) break;
  }

  // Report in standard parameters.
  fit.pi = objective.StandardParametersAt(context.best_x);
  fit.beta = base.combination * fit.pi;
  fit.cost = Cost(factor, fit.beta);
  fit.min_pseudo_inertia_eigenvalue = MinPseudoInertiaEigenvalues(fit.pi, n_links);
  fit.evaluations = context.evaluations;
  fit.status = nlopt_result_to_string(result);
  // Rounding-limited progress is the end of the search too (NLopt: "the
  // result is typically useful").
  fit.converged = result == NLOPT_SUCCESS || result == NLOPT_FTOL_REACHED || result == NLOPT_XTOL_REACHED ||
                  result == NLOPT_STOPVAL_REACHED || result == NLOPT_ROUNDOFF_LIMITED;
  return fit;
}

}  // namespace idbench
