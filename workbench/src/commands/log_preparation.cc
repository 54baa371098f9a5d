#include "idbench/workbench/commands/log_preparation.h"

#include <cmath>
#include <stdexcept>

#include "number_format.h"

namespace idbench {
namespace {

// Keeps the samples with T0 <= t <= T1 (and their line numbers).
void KeepTimeWindow(const std::string& path, const std::vector<double>& window, RecordedJointLog* recorded) {
  JointLog& log = recorded->log;
  const double t_first = log.t[0], t_last = log.t[log.n_samples() - 1];
  const std::string option = "--time-window " + Shortest(window[0]) + "," + Shortest(window[1]);
  if (window[0] < t_first || window[1] > t_last) {
    throw std::invalid_argument(path + ": " + option + " is not inside the log, which covers t = " + Shortest(t_first) +
                                " to " + Shortest(t_last) + " s");
  }
  Eigen::Index first = 0, last = log.n_samples() - 1;
  while (log.t[first] < window[0]) ++first;
  while (log.t[last] > window[1]) --last;
  const Eigen::Index n = last - first + 1;
  constexpr Eigen::Index kMinSamples = 4;
  if (n < kMinSamples) {
    throw std::invalid_argument(path + ": " + option + " keeps " + std::to_string(n) + " samples, expected at least " +
                                std::to_string(kMinSamples));
  }
  log.t = log.t.segment(first, n).eval();
  for (Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd, &log.tau}) {
    if (x->size() > 0) *x = x->middleRows(first, n).eval();
  }
  recorded->lines = std::vector<int>(recorded->lines.begin() + first, recorded->lines.begin() + first + n);
}

}  // namespace

bool LogPreparationOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!format.IsValid(why)) return false;
  if (!time_window.empty()) {
    if (time_window.size() != 2 || !std::isfinite(time_window[0]) || !std::isfinite(time_window[1]) ||
        !(time_window[0] < time_window[1])) {
      std::string given;
      for (double v : time_window) given += (given.empty() ? "" : ",") + Shortest(v);
      return fail("--time-window: expected T0,T1 [s] with T0 < T1, got " + given);
    }
  }
  if (!(max_gap_s >= 0.0 && max_gap_s <= kMaxGapS)) {
    return fail("--max-gap: expected 0 (10 median steps) to " + Shortest(kMaxGapS) + " s, got " + Shortest(max_gap_s));
  }
  std::string filter_why;
  if (!filter.IsValid(&filter_why)) return fail("--filter: " + filter_why);
  return true;
}

PreparedLog PrepareJointLog(const std::string& path, const RobotModel& model, const LogPreparationOptions& options) {
  return PrepareRecordedJointLog(ReadRecordedJointLog(path, model, options.format, options.torques), path, options);
}

PreparedLog PrepareRecordedJointLog(RecordedJointLog recorded, const std::string& path,
                                    const LogPreparationOptions& options) {
  PreparedLog out;
  out.warnings = recorded.warnings;
  if (recorded.torque_from_currents) out.notes.push_back(path + ": tau = K·i from the motor currents (--drive-gains)");

  // The time window.
  if (!options.time_window.empty()) {
    const int before = recorded.log.n_samples();
    KeepTimeWindow(path, options.time_window, &recorded);
    out.notes.push_back(path + ": time window " + Shortest(options.time_window[0]) + "–" +
                        Shortest(options.time_window[1]) + " s: " + std::to_string(recorded.log.n_samples()) + " of " +
                        std::to_string(before) + " samples");
  }
  JointLog& log = recorded.log;
  const bool has_qd = log.qd.size() > 0, has_qdd = log.qdd.size() > 0;
  if (has_qd && has_qdd) {
    out.derivatives = "qd, qdd from the log";
    out.log = std::move(log);
    return out;
  }

  // A uniform grid for the filter: irregular steps are resampled, a gap is an error.
  if (log.n_samples() < 3) {
    throw std::invalid_argument(path + ": " + std::to_string(log.n_samples()) +
                                " samples, too few to estimate qd, qdd by filtering");
  }
  JointLog uniform;
  const ResamplingSummary resampling = ResampleJointLog(log, {.max_gap_s = options.max_gap_s}, &uniform);
  if (resampling.status == ResamplingStatus::kGap) {
    const int line = recorded.lines[static_cast<size_t>(resampling.gap_sample)];
    throw std::invalid_argument(path + ":" + std::to_string(line) + ": column 't': " + resampling.BriefReport() +
                                "; split the log there or choose a --time-window without it (--max-gap sets the bound)");
  }
  if (resampling.status == ResamplingStatus::kResampled) out.notes.push_back(path + ": " + resampling.BriefReport());

  // qd, qdd by the zero-phase filter: from q, or from the recorded qd (qdd).
  LogFilterOptions derivatives = options.filter;
  derivatives.decimation = 1;
  derivatives.trim_s = 0.0;
  derivatives.filter_tau = false;
  try {
    out.log = ProcessJointLog(uniform, derivatives);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
  // tau is left unfiltered: it is filtered with the regressor (parallel filter).
  const Eigen::Index n = out.log.n_samples();
  out.parallel_filter = ParallelFilter{options.filter, static_cast<double>(n - 1) / (out.log.t[n - 1] - out.log.t[0])};
  out.derivatives = has_qd ? "qd from the log (filtered), qdd from the filtered qd"
                  : has_qdd ? "qd from the filtered q, qdd from the log (filtered)"
                            : "qd, qdd from the filtered q";
  return out;
}

}  // namespace idbench
