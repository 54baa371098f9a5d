#include "idbench/workbench/commands/log_preparation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "idbench/logs/open_joint_log.h"
#include "idbench/logs/recorded_joint_log_source.h"
#include "number_format.h"

namespace idbench {
namespace {

// Keeps the samples with T0 <= t <= T1 (and their line numbers).
void KeepTimeWindow(const std::string& path, const std::vector<double>& window, const std::string& field,
                    RecordedJointLog* recorded) {
  JointLog& log = recorded->log;
  const double t_first = log.t[0], t_last = log.t[log.n_samples() - 1];
  const std::string option = field + " " + Shortest(window[0]) + "," + Shortest(window[1]);
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
      return fail(window_field + ": expected T0,T1 [s] with T0 < T1, got " + given);
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
  // Every log is opened as a source (CSV, description, bag); gathered whole
  // here until the preparation itself streams.
  const std::unique_ptr<JointLogSource> source = OpenJointLog(path, model, options.format, options.torques);
  // A log description's time window, unless an option gives one too.
  const std::vector<double>& described = source->layout().time_window;
  if (described.empty()) return PrepareRecordedJointLog(ReadWholeLog(*source), path, options);
  if (!options.time_window.empty()) {
    throw std::invalid_argument(path + ": .time_window (" + Shortest(described[0]) + "," + Shortest(described[1]) +
                                ") and the option " + options.window_field + " (" + Shortest(options.time_window[0]) +
                                "," + Shortest(options.time_window[1]) + ") both give a time window: give it in one "
                                "place");
  }
  LogPreparationOptions windowed = options;
  windowed.time_window = described;
  windowed.window_field = ".time_window";
  return PrepareRecordedJointLog(ReadWholeLog(*source), path, windowed);
}

PreparedLog PrepareRecordedJointLog(RecordedJointLog recorded, const std::string& path,
                                    const LogPreparationOptions& options) {
  PreparedLog out;
  out.warnings = recorded.warnings;
  out.notes = recorded.notes;
  if (recorded.torque_from_currents) out.notes.push_back(path + ": tau = K·i from the motor currents (--drive-gains)");

  // The time window.
  if (!options.time_window.empty()) {
    const int before = recorded.log.n_samples();
    KeepTimeWindow(path, options.time_window, options.window_field, &recorded);
    std::string label = options.window_field;  // time_window → "time window"
    std::replace(label.begin(), label.end(), '_', ' ');
    out.notes.push_back(path + ": " + label + " " + Shortest(options.time_window[0]) + "–" +
                        Shortest(options.time_window[1]) + " s: " + std::to_string(recorded.log.n_samples()) + " of " +
                        std::to_string(before) + " samples");
  }
  JointLog& log = recorded.log;
  const bool has_qd = log.qd.size() > 0, has_qdd = log.qdd.size() > 0;
  if (has_qd && has_qdd) {
    out.derivatives = "qd, qdd from the log";
    // Decimation keeps every k-th sample, as it does after filtering (no
    // filter here: the recorded signals are used as they are).
    const int k = options.filter.decimation;
    if (k > 1) {
      const Eigen::Index n = (log.n_samples() + k - 1) / k;
      auto keep = [&](Eigen::MatrixXd* x) {
        if (x->size() == 0) return;
        Eigen::MatrixXd kept(n, x->cols());
        for (Eigen::Index s = 0; s < n; ++s) kept.row(s) = x->row(s * k);
        *x = std::move(kept);
      };
      Eigen::VectorXd t(n);
      for (Eigen::Index s = 0; s < n; ++s) t[s] = log.t[s * k];
      out.notes.push_back(path + ": decimation " + std::to_string(k) + ": one sample in " + std::to_string(k) +
                          " kept, " + std::to_string(n) + " of " + std::to_string(log.n_samples()));
      log.t = std::move(t);
      for (Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd, &log.tau}) keep(x);
    }
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

  // Enough samples for the zero-phase filter (it runs forward and backward
  // over the whole log), said in the user's terms.
  {
    const Eigen::Index n = uniform.n_samples();
    const double rate_hz = static_cast<double>(n - 1) / (uniform.t[n - 1] - uniform.t[0]);
    if (options.filter.cutoff_hz > 0.0 && options.filter.cutoff_hz < 0.5 * rate_hz) {
      const int needed =
          FiltFiltMinSamples(DesignButterworthLowPass(options.filter.order, options.filter.cutoff_hz, rate_hz));
      if (n < needed) {
        throw std::invalid_argument(path + ": " + std::to_string(n) + " samples, too few for the low-pass filter "
                                    "that estimates qd and qdd (order " + std::to_string(options.filter.order) +
                                    ": at least " + std::to_string(needed) + " samples); use a longer log or a wider "
                                    "time window, or a log that records qd and qdd");
      }
    }
  }

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
