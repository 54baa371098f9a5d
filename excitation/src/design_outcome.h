// What the excitation design's search came to (internal to excitation/src):
// each start's outcome line, and the explanation when no start was feasible
// or the design leaves parameters unexcited.
#pragma once

#include <string>
#include <vector>

#include "design_start.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench::internal {

// A start's outcome line and whether it got anywhere (DesignStartSummary).
void DescribeProgress(DesignStartSummary* s);

// No design, explained: summary, then one line per violation of check, then
// the "to relax:" lines of advice (feasibility_check.cc).
DesignInfeasibility ExplainInfeasibility(const std::string& summary, FeasibilityCheck check,
                                         std::vector<std::string> advice, bool before_search);

// The status of no design: kInfeasible after the search; before it,
// kNoRoom when an obstacle of the cell (not the ground) is violated (the cell
// is where the robot stands, not a malformed option), else kNoMotionPossible.
DesignStatus InfeasibilityStatus(const DesignInfeasibility& infeasibility);

// The least-violating point any start ended at, checked at the check rate:
// the kInfeasible result after the search (its trajectories that point and
// its start), the summary with one line per start saying what became of it
// (summaries[s].outcome).
DesignResult ExplainNoFeasibleStart(const RobotModel& model, const std::vector<JointLimits>& limits,
                                    const DesignOptions& options, const DesignProblem& problem,
                                    const std::vector<DesignStartSummary>& summaries, std::vector<StartRun>* runs);

// A design that meets the limits but leaves parameters unexcited (W of rank
// `rank` below the parameter count): the kNotExcited explanation names the
// rank, the parameters the least-squares classifier finds unidentifiable, with
// its reasons, and the joints the winning start held still; check is the
// design's own.
DesignInfeasibility ExplainUnexcited(const DesignRegressor& regressor, const Eigen::MatrixXd& W, int rank,
                                     const std::vector<std::string>& held_still, FeasibilityCheck check);

}  // namespace idbench::internal
