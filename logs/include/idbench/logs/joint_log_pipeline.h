// The joint-log pipeline: from a log file to the samples identification
// needs (README.md, "Joint logs"). Open it in its format (and transmission),
// keep the time window, bring irregular time stamps onto a uniform grid,
// estimate what the log did not record (qd, qdd) with the zero-phase filter
// (whose regressor and torques ident then filters in parallel), decimate.
// Streamed: a first pass over the source counts and checks; every later pass
// (StreamPreparedSamples) reads it again block by block, so memory does not
// grow with the log's length. ident/prepared_log_equations.h folds the
// prepared samples into equations.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_source.h"
#include "idbench/logs/log_resampling.h"
#include "idbench/logs/recorded_joint_log.h"
#include "idbench/logs/signal_filter.h"
#include "idbench/logs/streamed_log_filter.h"

namespace idbench {

struct LogPreparationOptions {
  JointLogFormat format;
  TorqueColumns torques = TorqueColumns::kRequired;  // kCurrents: tau holds the currents [A]
  std::vector<double> time_window;   // {T0, T1} [s]: keep T0 <= t <= T1; empty: the whole log
  std::string window_field = "time_window";  // the option field time_window came from, for messages
  LogFilterOptions filter{.trim_s = -1.0};  // for logs missing qd or qdd
  double max_gap_s = 0.0;            // [s] a longer step is an error; 0: 10 median steps
  // PreparedLog::log holds at most this many samples (every k-th beyond it);
  // 0: all of them (what needs the whole log, e.g. drive-gain estimation).
  Eigen::Index max_held_samples = kMaxHeldSamples;
  // For what holds a log whole (max_held_samples = 0): a log of more prepared
  // samples than this is refused after the first (counting) pass, before any
  // is held: std::invalid_argument naming the log, its samples, the bound and
  // the fix (time_window, or filter.decimation where it applies before the
  // samples are held). 0: no bound.
  Eigen::Index max_samples = 0;

  // 200 000 prepared samples of a 7-joint arm (t, q, qd, qdd, τ) are 46 MB.
  static constexpr Eigen::Index kMaxHeldSamples = 200000;

  static constexpr double kMaxGapS = 3600.0;
  // Checks the options alone; *why names the CLI option.
  bool IsValid(std::string* why) const;
};

// Progress and stop of one streamed pass over a log (a front end's progress
// bar and Cancel): the pass reports the fraction of its samples done, and
// ends early by throwing StreamStopped once *stop is set. Both are called and
// read on the thread running the pass.
struct StreamObserver {
  const std::atomic<bool>* stop = nullptr;
  std::function<void(double fraction)> progress;  // in [0, 1], non-decreasing within a pass
};

// Thrown by a pass whose StreamObserver::stop is set; RunIdentify turns it
// into IdentifyStatus::kCancelled.
struct StreamStopped : std::exception {
  const char* what() const noexcept override { return "stopped"; }
};

struct PreparedLog {
  // The prepared log (t, q, qd, qdd, τ or currents): every log_stride-th of
  // its n_samples samples, all of them up to max_held_samples (plots,
  // playback, Python). Identification streams every sample (FoldPreparedLog).
  JointLog log;
  Eigen::Index n_samples = 0;
  Eigen::Index log_stride = 1;
  std::optional<ParallelFilter> parallel_filter;  // set when qd or qdd were estimated
  std::string derivatives;  // where qd and qdd come from, for the user
  // τ read as held commands (JointLogFormat::torque_held): each sample's the
  // mean of its hold and the previous one's.
  bool torque_held = false;
  std::vector<std::string> notes;     // one line per step done (window, resampling), for stdout
  std::vector<std::string> warnings;  // for stderr

  // How to stream it again: the source's samples [first, first + n_raw)
  // (the time window), filtered (parallel_filter set; the recorded qd/qdd as
  // has_qd/has_qdd) or used as recorded, every `decimation`-th kept.
  std::shared_ptr<JointLogSource> source;
  std::string path;  // for messages
  Eigen::Index first = 0, n_raw = 0;
  bool has_qd = false, has_qdd = false;
  int decimation = 1;
};

// Reads `path` and prepares it. A log with both qd and qdd is used as read
// (no filter, so its time stamps need not be uniform); otherwise the log is
// resampled if its steps are not uniform (ResampleJointLog, on the log held
// whole: not streamed yet) and then filtered (StreamedLogFilter, as
// ProcessJointLog; its end transients kept for the parallel filter to drop). Throws std::invalid_argument naming the file (and line
// and column where there is one): the parser's errors, a time window outside
// the log or leaving fewer than 4 samples, a gap longer than the bound, or a
// log too short for the filter. A log with qd and qdd is decimated by
// filter.decimation (every k-th sample kept) without filtering. With an
// observer: its progress over the pass that holds the prepared samples, and
// StreamStopped once its stop is set.
PreparedLog PrepareJointLog(const std::string& path, const RobotModel& model, const LogPreparationOptions& options,
                            const StreamObserver* observer = nullptr);

// The same for a log already read (e.g. arrays from Python: lines are then
// row numbers); `source` names it in messages. Of options.format only
// torque_held is used (the rest was applied when the log was read).
PreparedLog PrepareRecordedJointLog(RecordedJointLog recorded, const std::string& source,
                                    const LogPreparationOptions& options);

// The same for a log opened as a source; `path` names it in messages.
PreparedLog PrepareJointLogSource(std::shared_ptr<JointLogSource> source, const std::string& path,
                                  const LogPreparationOptions& options, const StreamObserver* observer = nullptr);

// Streams the prepared samples of `log` to `sink`, in order: the source's
// samples [first, first + n_raw) filtered (StreamedLogFilter) or, used as
// recorded, every decimation-th. A progress line "<path>: <activity>: N % of
// M samples" goes to stderr once the pass takes more than 3 s (logs beyond
// one block), and to the observer, if any (StreamStopped once its stop is set).
void StreamPreparedSamples(const PreparedLog& log, const StreamedLogFilter::Sink& sink, const std::string& activity,
                           const StreamObserver* observer = nullptr);

}  // namespace idbench
