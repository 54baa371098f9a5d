// Reports: one self-contained directory with an HTML page and a PDF holding
// the experiment, the pose figure, the tables (truth, identified, errors,
// identifiability), the plots, and the exact command that reproduces it.
// `idbench report --out DIR` rebuilds it for a run's results.json; `--report`
// on `run` and `identify` writes it along with their results.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "idbench/workbench/commands/identify_command.h"
#include "idbench/render/plot.h"
#include "idbench/workbench/commands/run_command.h"

namespace idbench {

struct ReportTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

struct ReportPlot {
  std::string stem;     // file names plot_<stem>.png/.svg/.pdf
  std::string caption;
  PlotFigure figure;
};

struct ReportContent {
  std::string title;
  std::string command;  // reproduces the experiment
  std::vector<std::pair<std::string, std::string>> experiment;  // what was done, key → value
  std::string pose_figure_png;  // PNG bytes, written as figure.png ("" = none)
  std::string pose_caption;
  std::vector<ReportTable> tables;
  std::vector<ReportPlot> plots;
};

// A run's report: per-body tables, joint signals, true vs identified, the
// Euler blocks' spectra, and this motion against the other built-in one.
ReportContent MakeRunReportContent(const RobotModel& model, const RunOptions& options, const RunReport& report,
                                   std::string pose_figure_png);

// Where an identification's log came from. A recorded log's report sets the
// identified values beside the robot file's (a reference, not a truth) and
// calls its torques "measured"; a log simulated from the robot file has the
// file's values as its truth, and "truth" appears only then.
enum class LogOrigin { kRecorded, kSimulated };

// An identification's report: base parameters with σ against the robot
// file, fit and validation, joint signals, measured vs predicted torques (of
// the log and the held-out log), the base regressor's spectrum, the poses
// along the log, and the warnings (repeated ones collapsed). Joints and links
// by the robot file's names.
ReportContent MakeIdentifyReportContent(const RobotModel& model, const IdentifyOptions& options,
                                        const IdentifyReport& report, LogOrigin origin = LogOrigin::kRecorded);

// report.html, report.pdf, figure.png (with a pose figure) and the plots as
// PNG, SVG and PDF, to be written into `dir` (the HTML names them relatively).
std::vector<std::pair<std::filesystem::path, std::string>> FormatReportFiles(const ReportContent& content,
                                                                             const std::filesystem::path& dir);

// The run options recorded in a results.json (`source` names it in messages).
// Throws std::invalid_argument "source: key 'k': what" for a missing or
// mistyped key.
RunOptions RunOptionsFromResultsJson(const std::string& text, const std::string& source);

// HTML with &, <, >, " escaped.
std::string EscapeHtml(const std::string& text);

}  // namespace idbench
