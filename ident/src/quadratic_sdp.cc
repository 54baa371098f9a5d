#include "quadratic_sdp.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace idbench::internal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBarrierGrowth = 20.0;     // τ ← 20 τ after each centring
constexpr double kCentringTolerance = 1e-9; // Newton decrement² / 2 that ends a centring
constexpr double kArmijo = 0.25;
constexpr int kMaxStepsPerCentring = 100;

// A barrier problem over w: minimise τ (½ wᵀPw + qᵀw) − Σ log det S_j(w) − Σ log r_k(w).
struct BarrierProblem {
  Eigen::MatrixXd P;
  Eigen::VectorXd q;
  const std::vector<LmiBlock>* blocks = nullptr;
  const std::vector<LinearInequality>* rows = nullptr;
  int extra = -1;  // phase I: the variable s added to every block (s 𝟙) and row (+s); −1: none
  // Phase II: the objective is ‖R w − z‖² (P = 2RᵀR, q = −2Rᵀz), whose
  // gradient and increments are taken from the residual, not from P and q,
  // which lose the digits that matter near the optimum.
  const Eigen::MatrixXd* R = nullptr;
  const Eigen::VectorXd* z = nullptr;

  Eigen::VectorXd ObjectiveGradient(const Eigen::VectorXd& w) const {
    return R ? Eigen::VectorXd(2.0 * R->transpose() * (*R * w - *z)) : Eigen::VectorXd(P * w + q);
  }
  double ObjectiveChange(const Eigen::VectorXd& w, const Eigen::VectorXd& d) const {
    if (!R) return (P * w + q).dot(d) + 0.5 * d.dot(P * d);
    const Eigen::VectorXd Rd = *R * d;
    return (2.0 * (*R * w - *z) + Rd).dot(Rd);
  }

  int n() const { return static_cast<int>(q.size()); }
  int degree() const {  // Σ dim S_j + number of rows: the gap of a centred point is degree/τ
    int m = static_cast<int>(rows->size());
    for (const LmiBlock& b : *blocks) m += static_cast<int>(b.C.rows());
    return m;
  }
  double Objective(const Eigen::VectorXd& w) const { return 0.5 * w.dot(P * w) + q.dot(w); }
  Eigen::MatrixXd S(int j, const Eigen::VectorXd& w) const {
    const LmiBlock& b = (*blocks)[static_cast<size_t>(j)];
    Eigen::MatrixXd S = b.C;
    for (size_t i = 0; i < b.variables.size(); ++i) S += w[b.variables[i]] * b.B[i];
    if (extra >= 0) S.diagonal().array() += w[extra];
    return S;
  }
  double r(int k, const Eigen::VectorXd& w) const {
    const LinearInequality& row = (*rows)[static_cast<size_t>(k)];
    double value = row.c;
    for (const auto& [i, a] : row.a) value += a * w[i];
    return extra >= 0 ? value + w[extra] : value;
  }
  // Whether w lies in the strict interior, tested on S_j(w) and r_k(w)
  // themselves (PhiChange's factored increments lose that test where an
  // S_j is nearly singular).
  bool Inside(const Eigen::VectorXd& w) const { return std::isfinite(Phi(w, 0.0)); }
  // The barrier function at w, +∞ outside the strict interior.
  double Phi(const Eigen::VectorXd& w, double tau) const {
    double phi = tau * Objective(w);
    for (int j = 0; j < static_cast<int>(blocks->size()); ++j) {
      const Eigen::LLT<Eigen::MatrixXd> llt(S(j, w));
      if (llt.info() != Eigen::Success) return kInf;
      const Eigen::VectorXd d = llt.matrixL().toDenseMatrix().diagonal();
      if (!(d.minCoeff() > 0.0)) return kInf;
      phi -= 2.0 * d.array().log().sum();
    }
    for (int k = 0; k < static_cast<int>(rows->size()); ++k) {
      const double value = r(k, w);
      if (!(value > 0.0)) return kInf;
      phi -= std::log(value);
    }
    return std::isfinite(phi) ? phi : kInf;
  }
  // Phi(w + d) − Phi(w) for a strictly feasible w, computed from the
  // differences themselves (the quadratic's increment, log det(𝟙 + L⁻¹ΔS L⁻ᵀ),
  // log1p of the slacks) so that it stays accurate where τ f(w) is 10¹⁰
  // times larger; +∞ if w + d leaves the strict interior.
  double PhiChange(const Eigen::VectorXd& w, const Eigen::VectorXd& d, double tau) const {
    double change = tau * ObjectiveChange(w, d);
    for (int j = 0; j < static_cast<int>(blocks->size()); ++j) {
      const Eigen::LLT<Eigen::MatrixXd> llt(S(j, w));
      Eigen::MatrixXd dS = S(j, d) - (*blocks)[static_cast<size_t>(j)].C;  // linear part at d
      const Eigen::MatrixXd Linv_dS = llt.matrixL().solve(dS);
      Eigen::MatrixXd M = llt.matrixL().solve(Linv_dS.transpose());  // L⁻¹ ΔS L⁻ᵀ
      M.diagonal().array() += 1.0;
      const Eigen::LLT<Eigen::MatrixXd> step(M);
      if (step.info() != Eigen::Success) return kInf;
      const Eigen::VectorXd diagonal = step.matrixL().toDenseMatrix().diagonal();
      if (!(diagonal.minCoeff() > 0.0)) return kInf;
      change -= 2.0 * diagonal.array().log().sum();
    }
    for (int k = 0; k < static_cast<int>(rows->size()); ++k) {
      const double value = r(k, w), delta = r(k, d) - (*rows)[static_cast<size_t>(k)].c;
      if (!(value + delta > 0.0)) return kInf;
      change -= std::log1p(delta / value);
    }
    return std::isfinite(change) ? change : kInf;
  }
  // Gradient and Hessian of Phi at a strictly feasible w.
  void Derivatives(const Eigen::VectorXd& w, double tau, Eigen::VectorXd* grad, Eigen::MatrixXd* hess) const {
    *grad = tau * ObjectiveGradient(w);
    *hess = tau * P;
    for (int j = 0; j < static_cast<int>(blocks->size()); ++j) {
      const LmiBlock& b = (*blocks)[static_cast<size_t>(j)];
      const Eigen::MatrixXd S_inv = S(j, w).llt().solve(Eigen::MatrixXd::Identity(b.C.rows(), b.C.rows()));
      std::vector<Eigen::MatrixXd> Y;  // S⁻¹ B_i
      std::vector<int> index;
      for (size_t i = 0; i < b.variables.size(); ++i) {
        Y.push_back(S_inv * b.B[i]);
        index.push_back(b.variables[i]);
      }
      if (extra >= 0) {
        Y.push_back(S_inv);
        index.push_back(extra);
      }
      for (size_t i = 0; i < Y.size(); ++i) {
        (*grad)[index[i]] -= Y[i].trace();
        for (size_t l = 0; l <= i; ++l) {
          const double h = Y[i].cwiseProduct(Y[l].transpose()).sum();  // tr(Y_i Y_l)
          (*hess)(index[i], index[l]) += h;
          if (l != i) (*hess)(index[l], index[i]) += h;
        }
      }
    }
    for (int k = 0; k < static_cast<int>(rows->size()); ++k) {
      const LinearInequality& row = (*rows)[static_cast<size_t>(k)];
      const double value = r(k, w);
      std::vector<std::pair<int, double>> a = row.a;
      if (extra >= 0) a.emplace_back(extra, 1.0);
      for (const auto& [i, ai] : a) {
        (*grad)[i] -= ai / value;
        for (const auto& [l, al] : a) (*hess)(i, l) += ai * al / (value * value);
      }
    }
  }
};

// The Newton step −H⁻¹∇ from the symmetrically scaled system E H E (E H E
// unit diagonal: the barrier's curvature grows as 1/slack² near active
// constraints, and the scaling keeps the factorisation accurate), with a
// tiny diagonal shift where rounding makes it semidefinite. False if no
// descent direction comes out.
bool NewtonStep(const Eigen::VectorXd& grad, const Eigen::MatrixXd& hess, Eigen::VectorXd* step) {
  const Eigen::VectorXd E = hess.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  Eigen::MatrixXd scaled = E.asDiagonal() * hess * E.asDiagonal();
  *step = -E.cwiseProduct(scaled.ldlt().solve(E.cwiseProduct(grad)));
  if (step->allFinite() && grad.dot(*step) < 0.0) return true;
  scaled.diagonal().array() += 1e-12;
  *step = -E.cwiseProduct(scaled.ldlt().solve(E.cwiseProduct(grad)));
  return step->allFinite() && grad.dot(*step) < 0.0;
}

// Minimises Phi(·, τ) from a strictly feasible w by damped Newton steps;
// returns false if a step could not lower it (stalled). `stop` ends early.
template <typename Stop>
bool Centre(const BarrierProblem& problem, double tau, Eigen::VectorXd* w, int* steps, int max_steps, Stop stop) {
  Eigen::VectorXd grad;
  Eigen::MatrixXd hess;
  while (*steps < max_steps) {
    problem.Derivatives(*w, tau, &grad, &hess);
    Eigen::VectorXd step;
    if (!NewtonStep(grad, hess, &step)) return false;
    const double decrement2 = -grad.dot(step);
    if (decrement2 / 2.0 <= kCentringTolerance) return true;
    // Backtracking line search inside the domain. Within the region of
    // quadratic convergence (decrement < 1/4 for the self-concordant barrier,
    // Boyd & Vandenberghe §9.6.4) the full step is taken when it stays
    // feasible: there, Armijo's test would compare differences that rounding
    // has already swamped.
    const bool quadratic_region = decrement2 < 1.0 / 16.0;
    double alpha = 1.0;
    auto rejected = [&](double a) {
      const double change = problem.PhiChange(*w, a * step, tau);
      if (quadratic_region ? !std::isfinite(change) : change > -kArmijo * a * decrement2) return true;
      return !problem.Inside(*w + a * step);
    };
    while (rejected(alpha)) {
      alpha *= 0.5;
      if (alpha < 1e-14) return decrement2 < 1e-6;  // rounding floor near the centre
    }
    *w += alpha * step;
    ++*steps;
    if (stop(*w)) return true;
  }
  return false;
}

}  // namespace

bool IsStrictlyFeasible(const QuadraticSdp& problem, const Eigen::VectorXd& u) {
  BarrierProblem barrier;
  barrier.blocks = &problem.blocks;
  barrier.rows = &problem.rows;
  barrier.P = Eigen::MatrixXd::Zero(u.size(), u.size());
  barrier.q = Eigen::VectorXd::Zero(u.size());
  return std::isfinite(barrier.Phi(u, 0.0));
}

namespace {

// Throws std::invalid_argument for a malformed problem.
void CheckQuadraticSdp(const QuadraticSdp& problem) {
  const int n = problem.n_variables();
  if (problem.R.rows() != n || problem.z.size() != n || n < 1)
    throw std::invalid_argument("SolveQuadraticSdp: expected a square R and z of its size");
  for (const LmiBlock& b : problem.blocks) {
    if (b.C.rows() != b.C.cols() || b.variables.size() != b.B.size())
      throw std::invalid_argument("SolveQuadraticSdp: malformed block");
    for (size_t i = 0; i < b.variables.size(); ++i)
      if (b.variables[i] < 0 || b.variables[i] >= n || b.B[i].rows() != b.C.rows() || b.B[i].cols() != b.C.cols())
        throw std::invalid_argument("SolveQuadraticSdp: block variable or size out of range");
  }
  for (const LinearInequality& row : problem.rows)
    for (const auto& [i, a] : row.a)
      if (i < 0 || i >= n) throw std::invalid_argument("SolveQuadraticSdp: row variable out of range");
}

// Phase I: moves *u to a strictly feasible point of problem (it stays when
// it is one), counting the Newton steps in solution. False, with solution->u
// and solution->status saying why, when the data or the start are not finite
// or no point satisfies every constraint.
bool FindStrictlyFeasibleStart(const QuadraticSdp& problem, const QuadraticSdpOptions& options, Eigen::VectorXd* u,
                               QuadraticSdpSolution* solution) {
  const int n = problem.n_variables();
  // Phase I, when the start is not strictly feasible: minimise s + η f(u)
  // over (u, s) with S_j(u) + s 𝟙 ⪰ 0 and r_k(u) + s ≥ 0 until s < 0. The
  // small multiple of the objective, η = 10⁻⁴/f(u₀), keeps the barrier
  // problem bounded (without it, growing inertias drive −log det S to −∞)
  // and the Newton system regular, in the objective's own scale.
  BarrierProblem phase1;
  phase1.blocks = &problem.blocks;
  phase1.rows = &problem.rows;
  double worst = kInf;  // the least eigenvalue or slack at u
  BarrierProblem plain = phase1;
  plain.q = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < static_cast<int>(problem.blocks.size()); ++j)
    worst = std::min(worst, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(plain.S(j, *u), Eigen::EigenvaluesOnly)
                                .eigenvalues()[0]);
  for (int k = 0; k < static_cast<int>(problem.rows.size()); ++k) worst = std::min(worst, plain.r(k, *u));
  if (!std::isfinite(worst) || !u->allFinite() || !problem.R.allFinite() || !problem.z.allFinite()) {
    solution->u = *u;
    solution->status = "not finite: the problem's data or its start overflow (values beyond double precision)";
    return false;
  }
  if (!(worst > 0.0)) {
    // η trades the objective against the violation: where the data pin a
    // direction hard (a nearly noise-free log) even a small η can hold s
    // above 0, so a phase that ends infeasible is retried with η 10⁻⁴ times
    // smaller before the constraints are called contradictory.
    const Eigen::VectorXd u0 = *u;
    const double f0 = std::max((problem.R * u0 - problem.z).squaredNorm(), 1e-300);
    phase1.extra = n;
    Eigen::VectorXd w(n + 1);
    bool found = false;
    for (double eta = 1e-4 / f0; !found && eta > 1e-24 / f0; eta *= 1e-4) {
      phase1.P = Eigen::MatrixXd::Zero(n + 1, n + 1);
      phase1.P.topLeftCorner(n, n) = 2.0 * eta * problem.R.transpose() * problem.R;
      phase1.q = Eigen::VectorXd::Zero(n + 1);
      phase1.q.head(n) = -2.0 * eta * problem.R.transpose() * problem.z;
      phase1.q[n] = 1.0;
      w << u0, 1.0 - worst;
      // τ grows geometrically to 10¹⁴, so the loop ends; a start that is
      // not finite (values that overflow) ends it at once.
      for (double tau = 1.0 / std::max(1.0 - worst, 1.0);
           std::isfinite(tau) && tau > 0.0 && tau < 1e14 && !found && solution->newton_steps < options.max_newton_steps;
           tau *= kBarrierGrowth) {
        const int limit = std::min(options.max_newton_steps, solution->newton_steps + kMaxStepsPerCentring);
        Centre(phase1, tau, &w, &solution->newton_steps, limit,
               [&](const Eigen::VectorXd& v) { return found = v[n] < 0.0; });
        found = found || w[n] < 0.0;
      }
    }
    if (!found) {
      solution->u = w.head(n);
      solution->status = "infeasible: no parameters satisfy every constraint (the least violation is " +
                         std::to_string(w[n]) + ")";
      return false;
    }
    *u = w.head(n);
  }
  return true;
}

// Phase II from the strictly feasible u: the barrier's outer iterations;
// sets solution's u, objective, lower bound, gap, verdict and status.
void MinimiseFromInside(const QuadraticSdp& problem, const QuadraticSdpOptions& options, Eigen::VectorXd u,
                        QuadraticSdpSolution* solution) {
  const int n = problem.n_variables();
  // Phase II: f(u) = ‖R u − z‖² = ½ uᵀ(2RᵀR)u − 2(Rᵀz)ᵀu + zᵀz.
  BarrierProblem phase2;
  phase2.blocks = &problem.blocks;
  phase2.rows = &problem.rows;
  phase2.P = 2.0 * problem.R.transpose() * problem.R;
  phase2.q = -2.0 * problem.R.transpose() * problem.z;
  phase2.R = &problem.R;
  phase2.z = &problem.z;
  auto f = [&](const Eigen::VectorXd& v) { return (problem.R * v - problem.z).squaredNorm(); };
  // The dual function at Z_j = S_j⁻¹/τ, λ_k = 1/(τ r_k), a lower bound on
  // f*. These give Σ tr(Z_j S_j(u)) + Σ λ_k r_k(u) = m/τ (m = degree), so
  // with G = Σ tr(Z_j B_ij) + Σ λ_k a_k the Lagrangian is
  // f(v) − m/τ − Gᵀ(v − u), least where R v − z = y = ½ R⁻ᵀ G, and
  //   f(u) − g = m/τ + ‖y − e‖²,   e = R u − z,   y − e = ½ R⁻ᵀ (G − ∇f(u)):
  // the centred gap plus what the centring left, taken without the
  // cancellations of evaluating g itself (Z carries ε·cond(S_j) where a
  // block is nearly singular).
  const Eigen::PartialPivLU<Eigen::MatrixXd> Rt_lu(problem.R.transpose());
  const int degree = phase2.degree();
  auto lower_bound = [&](const Eigen::VectorXd& v, double tau) {
    Eigen::VectorXd g_dual = Eigen::VectorXd::Zero(n);  // G
    for (int j = 0; j < static_cast<int>(problem.blocks.size()); ++j) {
      const LmiBlock& b = problem.blocks[static_cast<size_t>(j)];
      const Eigen::MatrixXd Z = phase2.S(j, v).llt().solve(Eigen::MatrixXd::Identity(b.C.rows(), b.C.rows())) / tau;
      for (size_t i = 0; i < b.variables.size(); ++i) g_dual[b.variables[i]] += Z.cwiseProduct(b.B[i]).sum();
    }
    for (int k = 0; k < static_cast<int>(problem.rows.size()); ++k) {
      const double lambda = 1.0 / (tau * phase2.r(k, v));
      for (const auto& [i, a] : problem.rows[static_cast<size_t>(k)].a) g_dual[i] += lambda * a;
    }
    const Eigen::VectorXd centring = 0.5 * Rt_lu.solve(g_dual - phase2.ObjectiveGradient(v));  // y − e
    return f(v) - (degree / tau + centring.squaredNorm());
  };
  // A sharper certificate near the centre: one more Newton step Δu and the
  // dual point it implies, Z⁺ = (S⁻¹ − S⁻¹ S_Δ S⁻¹)/τ with S_Δ = Σ Δu_i B_i,
  // λ⁺ = (1 − aᵀΔu/r)/(τ r), both positive while Δuᵀ H_b Δu < 1 (H_b the
  // barrier's Hessian). At u⁺ = u + Δu they give
  //   f(u⁺) − g = (m − Δuᵀ H_b Δu)/τ + ¼ ‖R⁻ᵀ r_N‖²/τ²,
  // r_N = ∇Φ + H Δu the Newton system's residual: no term for how well u was
  // centred along the barrier's stiff directions, which rounding (ε·cond S_j)
  // leaves off centre by more than the tolerance. False where it does not apply.
  auto certify_after_step = [&](const Eigen::VectorXd& v, double tau, Eigen::VectorXd* next, double* gap) {
    Eigen::VectorXd grad_b, step;
    Eigen::MatrixXd hess_b;
    phase2.Derivatives(v, 0.0, &grad_b, &hess_b);  // the barrier alone
    const Eigen::VectorXd grad = tau * phase2.ObjectiveGradient(v) + grad_b;
    const Eigen::MatrixXd hess = tau * phase2.P + hess_b;
    if (!NewtonStep(grad, hess, &step)) return false;
    const double curvature = step.dot(hess_b * step);
    *next = v + step;
    if (!(curvature < 1.0) || !phase2.Inside(*next)) return false;
    *gap = (degree - curvature) / tau + 0.25 * Rt_lu.solve(grad + hess * step).squaredNorm() / (tau * tau);
    return std::isfinite(*gap);
  };
  // Outer iterations: centre, certify, raise τ. Rounding ends the progress
  // once τ f is ~10¹³ times the Newton decrement; the best certified point
  // (strictly feasible: only there is Z = S⁻¹/τ a dual point) is kept, and
  // two stalled centrings in a row that do not improve it end the solve.
  double tau = degree / std::max(f(u) + options.objective_offset, 1e-300);
  bool stalled = false;
  int fruitless_stalls = 0;
  double best_gap = kInf;  // absolute: f − g
  Eigen::VectorXd best_u = u;
  auto relative = [&](double gap, double objective) {
    return gap / std::max({objective + options.objective_offset, options.objective_floor, 1e-300});
  };
  // Each round either takes a Newton step or raises τ (finite, below 10³⁰⁰):
  // the loop ends.
  while (solution->newton_steps < options.max_newton_steps && std::isfinite(tau) && tau > 0.0 && tau < 1e300) {
    const int limit = std::min(options.max_newton_steps, solution->newton_steps + kMaxStepsPerCentring);
    stalled = !Centre(phase2, tau, &u, &solution->newton_steps, limit, [](const Eigen::VectorXd&) { return false; });
    double objective = f(u), gap = objective - lower_bound(u, tau);
    if (!std::isfinite(gap) || !phase2.Inside(u)) break;
    Eigen::VectorXd candidate = u, stepped;
    double stepped_gap = kInf;
    if (certify_after_step(u, tau, &stepped, &stepped_gap) && stepped_gap < gap) {
      candidate = stepped;
      objective = f(stepped);
      gap = stepped_gap;
    }
    const bool improved = gap < best_gap;
    if (improved) {
      best_gap = gap;
      best_u = candidate;
      solution->objective = objective;
      solution->lower_bound = objective - gap;
    }
    fruitless_stalls = stalled && !improved ? fruitless_stalls + 1 : 0;
    if (relative(best_gap, solution->objective) <= options.relative_gap || gap > 10.0 * best_gap || fruitless_stalls >= 2)
      break;
    tau *= kBarrierGrowth;
  }
  solution->u = best_u;
  solution->relative_gap = relative(best_gap, solution->objective);
  solution->feasible = phase2.Inside(best_u);
  solution->converged = solution->feasible && solution->relative_gap <= options.relative_gap;
  solution->status = solution->converged                                ? "converged"
                     : !std::isfinite(best_gap)                          ? "stopped: the objective or its bound is not finite"
                     : stalled                                           ? "stopped where rounding ends the progress"
                     : solution->newton_steps >= options.max_newton_steps ? "stopped: Newton step limit reached"
                                                                          : "stopped: the barrier parameter reached 1e300 before the gap closed";
}

}  // namespace

QuadraticSdpSolution SolveQuadraticSdp(const QuadraticSdp& problem, const QuadraticSdpOptions& options) {
  CheckQuadraticSdp(problem);
  const int n = problem.n_variables();
  QuadraticSdpSolution solution;
  Eigen::VectorXd u = options.start.size() == n ? options.start : Eigen::VectorXd::Zero(n);
  if (!FindStrictlyFeasibleStart(problem, options, &u, &solution)) return solution;
  MinimiseFromInside(problem, options, std::move(u), &solution);
  return solution;
}

}  // namespace idbench::internal
