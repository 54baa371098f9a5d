// A start's feasibility phase (StartRun::Centre) and the description of its
// worst constraint (design_start.h).
#include <algorithm>
#include <vector>

#include "design_start.h"

namespace idbench::internal {
namespace {

// The feasibility phase's state: its objective and the least-violating point.
struct CentreRun {
  StartRun* run = nullptr;
  double depth = 0.0;
  std::vector<double> values, gradients;  // nonlinear constraints and their gradients (row-major)
  // The best point: a feasible one of least f, else the least max violation.
  bool best_feasible = false;
  double best_key = kInf;
  Eigen::VectorXd best;
  nlopt_opt opt = nullptr;

  // Σ_i max(0, c_i + depth)² + Σ_rows max(0, r)², with its gradient.
  double Value(const double* theta, double* grad) {
    const DesignProblem& p = *run->problem;
    const size_t n = static_cast<size_t>(p.n_unknowns()), m = static_cast<size_t>(p.n_nonlinear_constraints());
    ++run->evaluations;
    if (run->control->stop && run->control->stop->load()) nlopt_force_stop(opt);
    values.resize(m);
    gradients.resize(m * n);
    p.NonlinearConstraints(theta, values.data(), grad ? gradients.data() : nullptr, &*run->ws);
    if (grad) std::fill(grad, grad + n, 0.0);
    double f = 0.0, worst = -kInf;
    for (size_t i = 0; i < m; ++i) {
      worst = std::max(worst, values[i]);
      const double v = values[i] + depth;
      if (v <= 0.0) continue;
      f += v * v;
      if (grad) {
        for (size_t u = 0; u < n; ++u) grad[u] += 2.0 * v * gradients[i * n + u];
      }
    }
    for (const LinearRow& row : p.rows()) {
      const double r = p.LinearValue(row, theta);
      worst = std::max(worst, r);
      if (r <= 0.0) continue;
      f += r * r;
      if (grad) {
        Eigen::Map<Eigen::VectorXd>(grad + row.joint * p.block(), row.coefficients.size()) += 2.0 * r * row.coefficients;
      }
    }
    const bool feasible = worst <= kFeasibilityTolerance;
    const double key = feasible ? f : worst;
    if ((feasible && !best_feasible) || (feasible == best_feasible && key < best_key)) {
      best_feasible = feasible, best_key = key;
      best = Eigen::Map<const Eigen::VectorXd>(theta, static_cast<Eigen::Index>(n));
    }
    return f;
  }

  static double Nlopt(unsigned, const double* x, double* grad, void* data) {
    return static_cast<CentreRun*>(data)->Value(x, grad);
  }
};

}  // namespace

int StartRun::Centre(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double depth, int budget,
                     Eigen::VectorXd* theta) {
  const int first = evaluations;
  if (problem->n_nonlinear_constraints() == 0 || budget < 1) return 0;
  // An infeasible point first slides back towards the home pose (q0 the
  // home, no motion: within the limits and clear, ChooseHome), along the
  // segment home + s (θ − home): 0.8 of the largest s in [0, 1] found
  // feasible by bisection (12 evaluations), so that what is left of the
  // motion is kept rather than lost.
  if (!Feasible(theta->data())) {
    Eigen::VectorXd home_theta = Eigen::VectorXd::Zero(problem->n_unknowns());
    for (int j = 0; j < problem->n_dof(); ++j) home_theta[j * problem->block()] = problem->home()[j];
    const Eigen::VectorXd direction = *theta - home_theta;
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 12 && evaluations - first < budget; ++i, ++evaluations) {
      const double mid = 0.5 * (lo + hi);
      const Eigen::VectorXd t = home_theta + mid * direction;
      (Feasible(t.data()) ? lo : hi) = mid;
    }
    const Eigen::VectorXd shrunk = home_theta + 0.8 * lo * direction;
    if (Feasible(shrunk.data())) *theta = shrunk;
  }
  CentreRun centre;
  centre.run = this;
  centre.depth = depth;
  // SLSQP without constraints but the box: a quasi-Newton descent on the
  // summed squared violation (smooth where the witness sample of each
  // constraint stays put).
  centre.opt = nlopt_create(NLOPT_LD_SLSQP, static_cast<unsigned>(problem->n_unknowns()));
  nlopt_set_min_objective(centre.opt, &CentreRun::Nlopt, &centre);
  nlopt_set_lower_bounds(centre.opt, lower.data());
  nlopt_set_upper_bounds(centre.opt, upper.data());
  nlopt_set_maxeval(centre.opt, std::max(1, budget - (evaluations - first)));
  nlopt_set_ftol_rel(centre.opt, 1e-6);
  nlopt_set_stopval(centre.opt, 0.0);  // every constraint depth inside: done
  double value = 0.0;
  nlopt_optimize(centre.opt, theta->data(), &value);
  nlopt_destroy(centre.opt);
  if (centre.best.size() > 0) *theta = centre.best;
  return evaluations - first;
}

std::string StartRun::WorstConstraint(const double* theta) {
  const double linear = problem->MaxLinearViolation(theta);
  NonlinearFeasible(theta);
  int worst = -1;
  for (size_t i = 0; i < nonlinear_values.size(); ++i) {
    if (worst < 0 || nonlinear_values[i] > nonlinear_values[static_cast<size_t>(worst)]) worst = static_cast<int>(i);
  }
  if (worst >= 0 && nonlinear_values[static_cast<size_t>(worst)] >= linear) {
    return problem->DescribeViolation(worst, nonlinear_values[static_cast<size_t>(worst)]);
  }
  return Format("the joint limits by %.3g %% of a limit", 100.0 * linear);
}

}  // namespace idbench::internal
