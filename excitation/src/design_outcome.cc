#include "design_outcome.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "excitation_design_internal.h"
#include "idbench/ident/least_squares.h"

namespace idbench {
namespace internal {

// A start's outcome line and whether it got anywhere (DesignStartSummary).
void DescribeProgress(DesignStartSummary* s) {
  // A criterion change below this (relative) is no change.
  constexpr double kUnchanged = 1e-9;
  if (std::isfinite(s->best_value)) {
    const bool from_infeasible = s->initial_violation > kFeasibilityTolerance;
    const bool improved = s->best_value < s->initial_value - kUnchanged * std::max(1.0, std::abs(s->initial_value));
    s->progressed = improved || from_infeasible;
    s->outcome = improved          ? "improved"
                 : from_infeasible ? "reached the limits from an infeasible start"
                                   : "no progress: the criterion did not improve on the start point";
    return;
  }
  s->progressed = s->final_violation < s->initial_violation - kFeasibilityTolerance;
  s->outcome = (s->progressed ? "infeasible: the violation fell from " : "no progress: infeasible, the violation went from ") +
               Format("%.3g to %.3g", s->initial_violation, s->final_violation) + " (of a limit's scale)";
}

// The least-violating point any start ended at, checked at the check rate:
// the kInfeasible result after the search.
DesignResult ExplainNoFeasibleStart(const RobotModel& model, const std::vector<JointLimits>& limits,
                                    const DesignOptions& options, const DesignProblem& problem,
                                    const std::vector<DesignStartSummary>& summaries, std::vector<StartRun>* runs) {
  int least = 0;
  double least_violation = kInf;
  for (size_t s = 0; s < runs->size(); ++s) {
    StartRun& run = (*runs)[s];
    if (run.last_theta.size() == 0) continue;
    const double* theta = run.last_theta.data();
    double violation = problem.MaxLinearViolation(theta);
    if (problem.n_nonlinear_constraints() > 0) {
      run.NonlinearFeasible(theta);
      violation = std::max(violation, *std::max_element(run.nonlinear_values.begin(), run.nonlinear_values.end()));
    }
    if (violation < least_violation) least_violation = violation, least = static_cast<int>(s);
  }
  const StartRun& run = (*runs)[static_cast<size_t>(least)];
  FeasibilityCheck check = CheckTrajectoryLimits(model, limits, problem.Trajectory(run.last_theta),
                                                 options.check_rate_hz, problem.clearance(), options.actuators);
  std::vector<std::string> advice = RelaxationAdvice(check, options, false);
  // What became of each start, then the check of the least violating one.
  std::string starts;
  for (size_t s = 0; s < summaries.size(); ++s) {
    starts += "  start " + std::to_string(s + 1) + ": " + summaries[s].outcome + "\n";
  }
  DesignResult result(problem.Trajectory(run.last_theta), problem.Trajectory(run.start_theta));
  result.status = DesignStatus::kInfeasible;
  result.infeasibility = ExplainInfeasibility(
      "no feasible design: no start met the limits (tightened by the margin " + Format("%g", options.margin) +
          ") and the clearance on the sample grid:\n" + starts + "where start " + std::to_string(least + 1) +
          " ended, checked at " + Format("%g", options.check_rate_hz) + " Hz:",
      std::move(check), std::move(advice), false);
  result.check = result.infeasibility.check;
  return result;
}

DesignInfeasibility ExplainUnexcited(const DesignRegressor& regressor, const Eigen::MatrixXd& W, int rank,
                                     const std::vector<std::string>& held_still, FeasibilityCheck check) {
  // Name what the limits leave unexcited (the least-squares classifier's reasons).
  const LeastSquaresSolution ls = SolveLeastSquares(W, Eigen::VectorXd::Zero(W.rows()), regressor.parameter_names());
  std::string unexcited;
  for (size_t i = 0; i < ls.identifiable.size(); ++i) {
    if (!ls.identifiable[i]) unexcited += "\n  " + ls.reason[i];
  }
  // Joints the start held still (their motion alone broke a constraint).
  std::string held;
  for (const std::string& h : held_still) held += "\n  held still: " + h;
  DesignInfeasibility out;
  out.explanation = "no design within these limits excites every parameter (rank " + std::to_string(rank) + " of " +
                    std::to_string(regressor.n_parameters()) + "); check the limits of the joints involved:" +
                    unexcited + held;
  out.check = std::move(check);
  return out;
}

}  // namespace internal

using internal::Format;

std::string DesignResult::Rejection() const {
  if (status != DesignStatus::kFeasible) {  // the explanation's first line, without its closing ':'
    std::string line = infeasibility.explanation.substr(0, infeasibility.explanation.find('\n'));
    if (!line.empty() && line.back() == ':') line.pop_back();
    return line;
  }
  if (!check.feasible()) return "the design violates the limits or the clearance at " + Format("%g Hz", check.rate_hz);
  const bool improved = value < initial_value - 1e-9 * std::max(1.0, std::abs(initial_value));
  if (!improved) {
    int none = 0;
    for (const DesignStartSummary& s : starts) none += s.progressed ? 0 : 1;
    return "no progress: the design is its start point (criterion unchanged); " + std::to_string(none) + " of " +
           std::to_string(starts.size()) + " starts made no progress";
  }
  return "";
}

RampedTrajectory DesignResult::RobotTrajectory() const {
  return RampedTrajectory(std::make_shared<FourierSeriesTrajectory>(trajectory), home, ramp_seconds);
}

}  // namespace idbench
