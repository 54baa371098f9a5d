// From a joint-log file to what identification needs (README.md, "Joint
// logs"): read it in its format, keep the time window, bring irregular time
// stamps onto a uniform grid, and estimate what the log did not record
// (qd, qdd) with the zero-phase filter, whose regressor and torques are then
// filtered in parallel.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/log_resampling.h"
#include "idbench/ident/signal_filter.h"
#include "idbench/logs/recorded_joint_log.h"

namespace idbench {

struct LogPreparationOptions {
  JointLogFormat format;
  TorqueColumns torques = TorqueColumns::kRequired;  // kCurrents: tau holds the currents [A]
  std::vector<double> time_window;   // {T0, T1} [s]: keep T0 <= t <= T1; empty: the whole log
  std::string window_field = "time_window";  // the option field time_window came from, for messages
  LogFilterOptions filter{.trim_s = -1.0};  // for logs missing qd or qdd
  double max_gap_s = 0.0;            // [s] a longer step is an error; 0: 10 median steps

  static constexpr double kMaxGapS = 3600.0;
  // Checks the options alone; *why names the CLI option.
  bool IsValid(std::string* why) const;
};

struct PreparedLog {
  JointLog log;                                  // t, q, qd, qdd, tau (or currents)
  std::optional<ParallelFilter> parallel_filter;  // set when qd or qdd were estimated
  std::string derivatives;  // where qd and qdd come from, for the user
  std::vector<std::string> notes;     // one line per step done (window, resampling), for stdout
  std::vector<std::string> warnings;  // for stderr
};

// Reads `path` and prepares it. A log with both qd and qdd is used as read
// (no filter, so its time stamps need not be uniform); otherwise the log is
// resampled if its steps are not uniform (ResampleJointLog) and then
// filtered (ProcessJointLog, its end transients kept for the parallel
// filter to drop). Throws std::invalid_argument naming the file (and line
// and column where there is one): the parser's errors, a time window outside
// the log or leaving fewer than 4 samples, a gap longer than the bound, or a
// log too short for the filter. A log with qd and qdd is decimated by
// filter.decimation (every k-th sample kept) without filtering.
PreparedLog PrepareJointLog(const std::string& path, const RobotModel& model, const LogPreparationOptions& options);

// The same for a log already read (e.g. arrays from Python: lines are then
// row numbers); `source` names it in messages. options.format is not used.
PreparedLog PrepareRecordedJointLog(RecordedJointLog recorded, const std::string& source,
                                    const LogPreparationOptions& options);

}  // namespace idbench
