// One start of the excitation design's search (internal to excitation/src):
// the NLopt glue (objective, linear rows, nonlinear constraints), the
// clearance re-check rounds, and the best feasible point it visits.
#pragma once

#include <nlopt.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "excitation_design_internal.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench::internal {

// SLSQP takes the grid rows within this fraction of their limit's scale
// (joint range, velocity or acceleration limit) of being active.
constexpr double kNearActive = 0.3;

// What one round of a start does (DesignExcitation runs the starts in two
// rounds when there are several; see there).
struct StartPlan {
  int budget = 0;                         // evaluations (max_evaluations for a single round)
  const Eigen::VectorXd* from = nullptr;  // the point to start from; null: the seeded StartPoint
  // A second stall ends the round (StartRun::deferred) instead of resuming
  // with COBYLA: the second round takes the start elsewhere.
  bool defer_stall = false;
  // What an earlier round of this start did, for its progress reports only
  // (evaluations counted on from there, the best value so far).
  int evaluations_before = 0;
  double best_before = kInf;
};

// One start of the optimizer: NLopt callbacks and the best feasible point.
struct StartRun {
  const DesignProblem* problem = nullptr;
  const DesignOptions* options = nullptr;
  const DesignControl* control = nullptr;
  int index = 0;
  DesignAlgorithm algorithm = DesignAlgorithm::kSlsqp;  // options->algorithm, or what a stalled start switched to
  std::optional<DesignProblem::Workspace> ws;
  nlopt_opt opt = nullptr;
  int evaluations = 0;
  int feasible_at = -1;  // see DesignStartSummary
  double best_value = kInf;
  Eigen::VectorXd best_theta;
  Eigen::VectorXd start_theta, last_theta;  // the start point; where the search ended
  std::vector<std::string> held_still;      // joints the start point holds still, and why (StartPoint)
  std::vector<double> nonlinear_values;

  Eigen::VectorXd pending_theta;  // see Objective
  double pending_value = kInf;

  // Stall watch: while stall_at > 0, the search stops (stalled) at that
  // evaluation unless it has visited a feasible point below stall_reference.
  // Each restart of the optimizer (more rows) moves stall_at to stall_window
  // evaluations after it: SLSQP gets that many uninterrupted.
  int stall_at = 0, stall_window = 0;
  double stall_reference = kInf;
  bool stalled = false;
  bool deferred = false;  // stalled twice with StartPlan::defer_stall: the round ended there
  int evaluations_before = 0;  // StartPlan's, for progress reports
  double best_before = kInf;

  // SLSQP's linear rows: those within kNearActive of their limit at the
  // points it was (re)started from. Its quadratic subproblem costs in
  // proportion to the rows, and most grid rows are far from any limit.
  // When SLSQP steps outside a row it did not take, the run stops there
  // (reselect) and resumes with the rows near that point added.
  std::vector<int> rows;
  std::vector<char> taken;  // per grid row
  bool reselect = false;
  Eigen::VectorXd reselect_theta;  // where it stepped outside

  // The rows near theta, and near also (when given) the other point.
  // keep: also the rows already taken (a resume within one Optimize, so that
  // two points outside different rows cannot alternate forever).
  void SelectRows(const double* theta, const double* also = nullptr, bool keep = false) {
    if (algorithm != DesignAlgorithm::kSlsqp) return;
    const std::vector<LinearRow>& all = problem->rows();
    if (!keep || taken.size() != all.size()) taken.assign(all.size(), 0);
    rows.clear();
    for (size_t i = 0; i < all.size(); ++i) {
      if (taken[i] || problem->LinearValue(all[i], theta) > -kNearActive ||
          (also && problem->LinearValue(all[i], also) > -kNearActive)) {
        taken[i] = 1;
        rows.push_back(static_cast<int>(i));
      }
    }
  }

  bool ViolatesUntakenRow(const double* theta) const {
    const std::vector<LinearRow>& all = problem->rows();
    for (size_t i = 0; i < all.size(); ++i) {
      if (!taken[i] && problem->LinearValue(all[i], theta) > kFeasibilityTolerance) return true;
    }
    return false;
  }

  // Whether another Optimize may follow (each has its own evaluation budget).
  static bool Resumable(nlopt_result result) { return result != NLOPT_FORCED_STOP && result != NLOPT_MAXTIME_REACHED; }

  // Runs the optimizer from *theta (left at its last point) for at most
  // max_evaluations; SLSQP resumes with more rows while its result violates
  // rows it did not take.
  nlopt_result Optimize(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                        std::chrono::steady_clock::time_point t_begin, Eigen::VectorXd* theta, int budget);

  // The feasibility phase (start_recovery.cc): an infeasible *theta first
  // slides back towards the home pose until feasible; then, from there, minimises
  //   Σ_i max(0, c_i + depth)² + Σ_rows max(0, r)²
  // over the nonlinear constraints c_i (normalised, ≤ 0 met) and the linear
  // rows r, within the box, for at most `budget` evaluations (counted in
  // evaluations): it leaves an infeasible point towards feasibility and a
  // feasible one on a constraint's edge `depth` inside. *theta is left at the
  // point of least max violation it visited; returns the evaluations used.
  int Centre(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double depth, int budget,
             Eigen::VectorXd* theta);
  // The worst constraint at theta and by how much it is broken, for a
  // start's line (DesignProblem::DescribeViolation, or "the joint limits by 4 % of a limit").
  std::string WorstConstraint(const double* theta);


  // Evaluates the nonlinear constraints into nonlinear_values.
  bool NonlinearFeasible(const double* theta) {
    nonlinear_values.resize(static_cast<size_t>(problem->n_nonlinear_constraints()));
    if (nonlinear_values.empty()) return true;
    problem->NonlinearConstraints(theta, nonlinear_values.data(), nullptr, &*ws);
    return *std::max_element(nonlinear_values.begin(), nonlinear_values.end()) <= kFeasibilityTolerance;
  }

  // The worst normalised violation of every constraint at theta (≤ 0: feasible).
  double Violation(const double* theta) {
    double v = problem->MaxLinearViolation(theta);
    NonlinearFeasible(theta);
    for (double c : nonlinear_values) v = std::max(v, c);
    return v;
  }

  bool Feasible(const double* theta) {
    return problem->MaxLinearViolation(theta) <= kFeasibilityTolerance && NonlinearFeasible(theta);
  }

  // Penalty for the unconstrained (SBPLX) form: squared normalised violations,
  // the nonlinear ones from *nonlinear_values (already evaluated at theta).
  double Penalty(const double* theta) const {
    double p = 0.0;
    for (const LinearRow& row : problem->rows()) {
      const double v = problem->LinearValue(row, theta);
      if (v > 0.0) p += v * v;
    }
    for (double v : nonlinear_values) p += v > 0.0 ? v * v : 0.0;
    return 1e4 * p;
  }

  void Consider(const double* theta, double value) {
    if (feasible_at < 0) feasible_at = evaluations;
    if (value >= best_value) return;
    best_value = value;
    best_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
  }

  // The criterion, and the best feasible point so far. When NLopt evaluates
  // the nonlinear constraints itself (right after the objective, at the same
  // x), a point that meets the linear rows waits for them (pending) rather
  // than computing them twice.
  double Objective(const double* theta, double* grad) {
    ++evaluations;
    if (control->stop && control->stop->load()) nlopt_force_stop(opt);
    const double c = problem->Criterion(theta, grad, &*ws);
    const bool linear_ok = problem->MaxLinearViolation(theta) <= kFeasibilityTolerance;
    if (!linear_ok && !taken.empty() && ViolatesUntakenRow(theta)) {
      reselect = true;
      reselect_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
      nlopt_force_stop(opt);
    }
    const bool sbplx = algorithm == DesignAlgorithm::kSbplx;
    pending_theta.resize(0);
    bool feasible = linear_ok;
    if (problem->n_nonlinear_constraints() > 0 && sbplx) {
      feasible = linear_ok && NonlinearFeasible(theta);
    } else if (problem->n_nonlinear_constraints() > 0) {
      feasible = false;
      if (linear_ok && c < best_value) {
        pending_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
        pending_value = c;
      }
    }
    if (feasible) Consider(theta, c);
    if (stall_at > 0 && evaluations >= stall_at && !(best_value < stall_reference) && pending_theta.size() == 0) {
      stalled = true;
      nlopt_force_stop(opt);
    }
    if (control->progress && evaluations % 20 == 0) control->progress({index, evaluations_before + evaluations, std::min(best_value, best_before), linear_ok});
    return sbplx ? c + Penalty(theta) : c;
  }

  static double NloptObjective(unsigned, const double* x, double* grad, void* data) {
    return static_cast<StartRun*>(data)->Objective(x, grad);
  }

  // The selected grid rows (SLSQP).
  static void NloptLinear(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    const auto* self = static_cast<StartRun*>(data);
    const DesignProblem& p = *self->problem;
    if (grad) std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
    for (unsigned i = 0; i < m; ++i) {
      const LinearRow& row = p.rows()[static_cast<size_t>(self->rows[i])];
      result[i] = p.LinearValue(row, x);
      if (grad) {
        std::copy(row.coefficients.data(), row.coefficients.data() + row.coefficients.size(),
                  grad + static_cast<size_t>(i) * n + static_cast<size_t>(row.joint * p.block()));
      }
    }
  }

  // One constraint per joint × quantity: the worst grid row (COBYLA, MMA),
  // with that row's gradient.
  static void NloptGrouped(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    const auto* self = static_cast<StartRun*>(data);
    const DesignProblem& p = *self->problem;
    std::fill(result, result + m, -kInf);
    std::vector<const LinearRow*> worst(m, nullptr);
    for (const LinearRow& row : p.rows()) {
      const double v = p.LinearValue(row, x);
      if (v > result[row.group]) result[row.group] = v, worst[static_cast<size_t>(row.group)] = &row;
    }
    if (!grad) return;
    std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
    for (unsigned i = 0; i < m; ++i) {
      if (const LinearRow* row = worst[i]) {
        std::copy(row->coefficients.data(), row->coefficients.data() + row->coefficients.size(),
                  grad + static_cast<size_t>(i) * n + static_cast<size_t>(row->joint * p.block()));
      } else {
        result[i] = -1.0;  // a joint without position limits
      }
    }
  }

  static void NloptNonlinear(unsigned m, double* result, unsigned, const double* x, double* grad, void* data) {
    auto* self = static_cast<StartRun*>(data);
    self->problem->NonlinearConstraints(x, result, grad, &*self->ws);
    const Eigen::VectorXd& p = self->pending_theta;
    if (p.size() > 0 && std::equal(p.data(), p.data() + p.size(), x) &&
        *std::max_element(result, result + m) <= kFeasibilityTolerance) {
      self->Consider(x, self->pending_value);
    }
    self->pending_theta.resize(0);
  }
};

// Start s of DesignExcitation from its seeded start point (or plan.from) to
// its best point within plan.budget evaluations (and the repair rounds' third
// of it), into *run (its run state, kept for ExplainNoFeasibleStart) and *summary.
// `problem` gains the clearance instants the fine check adds (in this start's
// workspace). t_begin is when the design began (for options.max_seconds).
void RunStart(int s, const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
              const DesignOptions& options, const DesignControl& control, const DesignProblem& problem,
              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
              std::chrono::steady_clock::time_point t_begin, const StartPlan& plan, StartRun* run_out,
              DesignStartSummary* summary_out);

}  // namespace idbench::internal
