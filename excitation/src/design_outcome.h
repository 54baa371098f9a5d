// What the excitation design's search came to (internal to excitation/src):
// each start's outcome line, and the explanation when no start was feasible.
#pragma once

#include <vector>

#include "design_start.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench::internal {

// A start's outcome line and whether it got anywhere (DesignStartSummary).
void DescribeProgress(DesignStartSummary* s);

// The least-violating point any start ended at, checked at the check rate:
// thrown as InfeasibleDesign after the search, its summary with one line per
// start saying what became of it (summaries[s].outcome).
[[noreturn]] void ExplainNoFeasibleStart(const RobotModel& model, const std::vector<JointLimits>& limits,
                                         const DesignOptions& options, const DesignProblem& problem,
                                         const std::vector<DesignStartSummary>& summaries,
                                         std::vector<StartRun>* runs);

}  // namespace idbench::internal
