#include "design_start.h"

#include "design_outcome.h"

#include <cmath>

namespace idbench::internal {

nlopt_result StartRun::Optimize(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                std::chrono::steady_clock::time_point t_begin, Eigen::VectorXd* theta, int budget) {
  const nlopt_algorithm algorithm = this->algorithm == DesignAlgorithm::kSlsqp    ? NLOPT_LD_SLSQP
                                    : this->algorithm == DesignAlgorithm::kMma    ? NLOPT_LD_MMA
                                    : this->algorithm == DesignAlgorithm::kCobyla ? NLOPT_LN_COBYLA
                                                                                     : NLOPT_LN_SBPLX;
  const unsigned n_theta = static_cast<unsigned>(problem->n_unknowns());
  nlopt_result result = NLOPT_SUCCESS;
  const int first_evaluation = evaluations;
  for (;;) {
    if (stall_at > 0) stall_at = std::max(stall_at, evaluations + stall_window);
    opt = nlopt_create(algorithm, n_theta);
    nlopt_set_min_objective(opt, &StartRun::NloptObjective, this);
    nlopt_set_lower_bounds(opt, lower.data());
    nlopt_set_upper_bounds(opt, upper.data());
    // SLSQP with one max-row per limit stalls (cond 170 where the rows reach
    // 42 for puma560); MMA's dual is too slow with many rows, so it and
    // COBYLA take the max.
    if (algorithm == NLOPT_LD_SLSQP) {
      const std::vector<double> tol(rows.size(), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptLinear, this,
                                       tol.data());
    } else if (algorithm != NLOPT_LN_SBPLX) {
      const std::vector<double> tol(static_cast<size_t>(problem->n_groups()), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptGrouped, this,
                                       tol.data());
    }
    if (problem->n_nonlinear_constraints() > 0 && algorithm != NLOPT_LN_SBPLX) {
      const std::vector<double> tol(static_cast<size_t>(problem->n_nonlinear_constraints()), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptNonlinear, this,
                                       tol.data());
    }
    if (algorithm == NLOPT_LN_COBYLA || algorithm == NLOPT_LN_SBPLX) {
      // A first step of 10 % of each unknown's box (COBYLA's and SBPLX's scale).
      const Eigen::VectorXd step = 0.1 * (upper - lower).cwiseMin(2.0 * theta->cwiseAbs().cwiseMax(1e-2));
      nlopt_set_initial_step(opt, step.data());
    }
    nlopt_set_maxeval(opt, std::max(1, budget - (evaluations - first_evaluation)));
    nlopt_set_ftol_rel(opt, 1e-10);  // looser (1e-7) stops SLSQP on plateaus: cond 50 instead of 43
    nlopt_set_xtol_rel(opt, 1e-10);
    if (options->max_seconds > 0.0) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
      nlopt_set_maxtime(opt, std::max(1e-3, options->max_seconds - elapsed));
    }
    double value = 0.0;
    reselect = false;
    result = nlopt_optimize(opt, theta->data(), &value);
    nlopt_destroy(opt);
    opt = nullptr;
    if (!reselect || stalled || (control->stop && control->stop->load()) ||
        evaluations - first_evaluation >= budget) {
      break;
    }
    // Resume from the best feasible point (else where it stepped out) with
    // the rows near both.
    if (best_theta.size() > 0) *theta = best_theta;
    else *theta = reselect_theta;
    SelectRows(theta->data(), reselect_theta.data(), true);
  }
  if (reselect && result == NLOPT_FORCED_STOP && !(control->stop && control->stop->load())) {
    result = NLOPT_MAXEVAL_REACHED;  // stopped to resume, but out of evaluations
  }
  return result;
}

namespace {

// theta with every joint's coefficients scaled by the largest common factor
// (≥ 1, at most 1024) that keeps the linear rows met: where a start scaled
// down for the nonlinear constraints would reach the kinematic limits
// (theta itself when that factor is under 2: a start hardly scaled down).
Eigen::VectorXd GrownToLinearLimits(const DesignProblem& problem, const Eigen::VectorXd& theta) {
  auto scaled = [&](double s) {
    Eigen::VectorXd t = theta;
    for (int j = 0; j < problem.n_dof(); ++j) t.segment(j * problem.block() + 1, 2 * problem.harmonics()) *= s;
    return t;
  };
  double lo = 1.0, hi = 1024.0;
  if (problem.MaxLinearViolation(scaled(lo).data()) > 0.0) return theta;
  for (int i = 0; i < 30; ++i) {
    const double mid = std::sqrt(lo * hi);
    (problem.MaxLinearViolation(scaled(mid).data()) <= 0.0 ? lo : hi) = mid;
  }
  // A start not scaled down (the 90 % of StartPoint) keeps its own rows.
  return lo > 2.0 ? scaled(lo) : theta;
}

}  // namespace

void RunStart(int s, const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
              const DesignOptions& options, const DesignControl& control, const DesignProblem& problem,
              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
              std::chrono::steady_clock::time_point t_begin, const StartPlan& plan, StartRun* run_out,
              DesignStartSummary* summary_out) {
  // A start that has not improved on its start point (nor, infeasible, met
  // the constraints) after this many evaluations is stalled: it is moved
  // inside its constraints (Centre) and resumed from there.
  constexpr int kStallEvaluations = 30;
  // How far inside the nonlinear constraints the feasibility phase aims
  // (normalised: 1 cm of clearance, 10 % of a torque limit), and its budget.
  constexpr double kCentreDepth = 0.1;
  constexpr int kCentreEvaluations = 60;
  StartRun& run = *run_out;
  run.problem = &problem;
  run.options = &options;
  run.control = &control;
  run.index = s;
  run.algorithm = options.algorithm;
  run.ws.emplace(problem);
  run.evaluations_before = plan.evaluations_before, run.best_before = plan.best_before;
  Eigen::VectorXd theta = plan.from ? *plan.from
                                    : problem.StartPoint(options.seed + static_cast<unsigned>(s), &*run.ws, &run.held_still);
  run.start_theta = theta;
  DesignStartSummary& summary = *summary_out;
  summary.initial_value = problem.Criterion(theta.data(), nullptr, &*run.ws);
  summary.initial_violation = run.Violation(theta.data());
  run.best_value = kInf;
  // Takes theta as the best point when it is feasible (after a feasibility phase).
  auto take_if_feasible = [&]() {
    if (!run.Feasible(theta.data())) return false;
    const double value = problem.Criterion(theta.data(), nullptr, &*run.ws);
    if (run.feasible_at < 0) run.feasible_at = run.evaluations;
    if (value < run.best_value) run.best_value = value, run.best_theta = theta;
    return true;
  };
  take_if_feasible();
  const int budget = plan.budget;
  auto remaining = [&]() { return std::max(1, budget - run.evaluations); };

  // The story of this start for its line: what was wrong and what was done.
  std::string story;
  for (const std::string& held : run.held_still) story += (story.empty() ? "held still: " : ", ") + held;
  const bool recover = problem.n_nonlinear_constraints() > 0 && options.algorithm != DesignAlgorithm::kSbplx;
  // An infeasible start: first the feasibility phase (the linear limits alone
  // SLSQP meets by itself).
  if (recover && run.best_theta.size() == 0 && problem.n_nonlinear_constraints() > 0) {
    story += (story.empty() ? "" : "; ") + ("infeasible (" + run.WorstConstraint(theta.data()) + ")");
    const int used = run.Centre(lower, upper, kCentreDepth, std::min(kCentreEvaluations, budget / 3), &theta);
    story += take_if_feasible() ? Format(" -> feasible after %g evaluations", used)
                                : Format(" -> still infeasible after %g evaluations (", used) +
                                      run.WorstConstraint(theta.data()) + ")";
  }

  // SLSQP takes the grid rows near the limits (see SelectRows), MMA and
  // COBYLA one max-row per limit. When SLSQP ends outside rows it did
  // not take, they join and it resumes from there. A stall watch stops it
  // early when it gets nowhere; it then resumes from inside the constraints.
  if (recover) {
    run.stall_window = kStallEvaluations;
    run.stall_at = run.evaluations + kStallEvaluations, run.stall_reference = run.best_value;
  }
  // The rows near the start and near it grown to the kinematic limits (a
  // start scaled down for the clearance or torques grows back: without them
  // SLSQP restarts for more rows at each step, losing its Hessian).
  const Eigen::VectorXd grown = recover ? GrownToLinearLimits(problem, theta) : theta;
  run.SelectRows(theta.data(), grown.data());
  const Eigen::VectorXd searched_from = theta;
  nlopt_result result = run.Optimize(lower, upper, t_begin, &theta, remaining());
  run.stall_at = 0;
  // A stalled start resumes from its best point (or where it began, when it
  // found none): first moved inside its constraints (the feasibility phase),
  // and when that does not help (or the point is already inside), with
  // COBYLA (derivative-free, one row per limit), which SLSQP's stalls do not hold.
  for (int attempt = 0; run.stalled && attempt < 2; ++attempt) {
    run.stalled = false;
    theta = run.best_theta.size() > 0 ? run.best_theta : searched_from;
    story += (story.empty() ? "" : "; ") + Format("no progress in %g evaluations (", kStallEvaluations) +
             (run.best_theta.size() > 0 ? std::string("feasible, the criterion unchanged") : run.WorstConstraint(theta.data())) +
             ")";
    const Eigen::VectorXd stalled_at = theta;
    bool moved = false;
    if (attempt == 0) {
      const int used = run.Centre(lower, upper, kCentreDepth, std::min(kCentreEvaluations, remaining() / 3), &theta);
      moved = theta != stalled_at;
      const bool inside = run.Feasible(theta.data());
      if (inside) take_if_feasible();
      if (moved) {
        story += Format(inside ? " -> moved inside in %g evaluations, resumed" : " -> centring failed in %g evaluations, resumed",
                        used);
      }
    }
    if (!moved && plan.defer_stall) {
      run.deferred = true;
      story += " -> left for the second round";
      break;
    }
    if (!moved) {
      run.algorithm = DesignAlgorithm::kCobyla;
      story += " -> resumed with cobyla";
    } else if (run.algorithm == DesignAlgorithm::kSlsqp) {
      run.stall_at = run.evaluations + kStallEvaluations, run.stall_reference = run.best_value;
    }
    run.SelectRows(theta.data(), grown.data(), true);
    result = run.Optimize(lower, upper, t_begin, &theta, remaining());
    run.stall_at = 0;
  }

  // Clearance is constrained on the grid; where the fine check finds the
  // links closer between grid instants, those instants join this start's
  // grid and the search resumes from its best point (at most twice). The
  // rounds share one third of max_evaluations: a repair near a found
  // optimum, not a second search (which doubled a start's time).
  const int repair_end = run.evaluations + std::max(1, budget / 3);
  for (int round = 0; round < 2 && problem.clearance() && run.best_theta.size() > 0 && run.Resumable(result);
       ++round) {
    const FeasibilityCheck fine = CheckTrajectoryLimits(regressor.model(), limits,
                                                        problem.Trajectory(run.best_theta),
                                                        options.check_rate_hz, problem.clearance());
    bool added = false;
    for (const ConstraintMargin& m : fine.margins) {
      if (m.quantity == "clearance" && m.margin < 0.0) problem.AddClearanceInstant(m.time, &*run.ws), added = true;
    }
    if (!added || run.evaluations >= repair_end) break;
    theta = run.best_theta;
    run.best_value = kInf;
    run.best_theta.resize(0);
    run.SelectRows(theta.data());
    result = run.Optimize(lower, upper, t_begin, &theta, repair_end - run.evaluations);
  }
  run.last_theta = theta;
  summary.best_value = run.best_value;
  summary.evaluations = run.evaluations;
  summary.feasible_at = run.feasible_at;
  summary.status = result == NLOPT_FORCED_STOP ? "stopped" : nlopt_result_to_string(result);
  summary.final_violation = run.Violation(theta.data());
  DescribeProgress(&summary);
  if (!story.empty()) summary.outcome = story + "; " + summary.outcome;
}

}  // namespace idbench::internal
