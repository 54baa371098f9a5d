// Reports (report_command.h) of an excitation design and of a comparison of
// motions, for `--report` on `idbench design` and `idbench compare`.
#pragma once

#include "idbench/workbench/commands/compare_command.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench {

// The designed motion's poses, its joint signals (with the torques it needs),
// identifiability before and after, the 1 kHz margins per joint and pair,
// the starts, and the spectra of W before and after.
ReportContent MakeDesignReportContent(const RobotModel& model, const DesignCommandOptions& options,
                                      const DesignCommandReport& report);

// The motions side by side (cond, log det, σ_min, realised cond, Monte-Carlo
// error), %σ per parameter, the limit checks, and bars of the three measures.
ReportContent MakeCompareReportContent(const CompareOptions& options, const CompareReport& report);

}  // namespace idbench
