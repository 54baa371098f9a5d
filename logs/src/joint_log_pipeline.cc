#include "idbench/logs/joint_log_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>

#include "held_torque_source.h"
#include "idbench/logs/open_joint_log.h"
#include "idbench/logs/prefetching_joint_log_source.h"
#include "idbench/logs/recorded_joint_log_source.h"
#include "number_format.h"

namespace idbench {

bool LogPreparationOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!format.IsValid(why)) return false;
  if (!time_window.empty()) {
    // Say which of the three is wrong: the count, a bound not a finite number, the order.
    std::string given;
    for (double v : time_window) given += (given.empty() ? "" : ",") + Shortest(v);
    if (time_window.size() != 2) {
      return fail(window_field + ": expected two values T0,T1 [s], got " + std::to_string(time_window.size()) +
                  " (" + given + ")");
    }
    if (!std::isfinite(time_window[0]) || !std::isfinite(time_window[1]))
      return fail(window_field + ": expected finite bounds T0,T1 [s] (a number of seconds each), got " + given);
    if (!(time_window[0] < time_window[1])) return fail(window_field + ": expected T0,T1 [s] with T0 < T1, got " + given);
  }
  if (!(max_gap_s >= 0.0 && max_gap_s <= kMaxGapS)) {
    return fail("max_gap_s: expected 0 (10 median steps) to " + Shortest(kMaxGapS) + " s, got " + Shortest(max_gap_s));
  }
  if (max_samples < 0) return fail("max_samples: expected >= 0 (0: no bound), got " + std::to_string(max_samples));
  std::string filter_why;
  if (!filter.IsValid(&filter_why)) return fail("filter." + filter_why);
  return true;
}

namespace {

// A pass's progress: to the observer (which may stop it), and as a line on
// stderr, at most every 2 s, once the work has taken 3 s (when `print`).
class ProgressLine {
 public:
  ProgressLine(std::string what, bool print, const StreamObserver* observer)
      : what_(std::move(what)), print_(print), observer_(observer) {}
  ~ProgressLine() {
    if (shown_) std::fprintf(stderr, "\r%s: done%30s\n", what_.c_str(), "");
  }
  // Throws StreamStopped once the observer's stop is set.
  void Update(Eigen::Index done, Eigen::Index total) {
    const double fraction = std::clamp(static_cast<double>(done) / static_cast<double>(std::max<Eigen::Index>(total, 1)),
                                       0.0, 1.0);
    if (observer_) {
      if (observer_->stop && observer_->stop->load()) throw StreamStopped();
      if (observer_->progress) observer_->progress(fraction);
    }
    if (!print_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(3) || now - last_ < std::chrono::seconds(2)) return;
    last_ = now;
    shown_ = true;
    std::fprintf(stderr, "\r%s: %.0f %% of %lld samples", what_.c_str(), 100.0 * fraction,
                 static_cast<long long>(total));
    std::fflush(stderr);
  }

 private:
  std::string what_;
  bool print_;
  const StreamObserver* observer_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_;
  bool shown_ = false;
};

// Streams the prepared samples of `log` to `sink`, in order: the source's
// samples [first, first + n_raw) filtered (StreamedLogFilter) or, used as
// recorded, every decimation-th.
void StreamSamples(const PreparedLog& log, const StreamedLogFilter::Sink& sink, ProgressLine* progress) {
  JointLogSource& source = *log.source;
  source.Rewind();
  const int n_dof = source.layout().n_dof;
  std::optional<StreamedLogFilter> filter;
  if (log.parallel_filter) {
    filter.emplace(log.parallel_filter->filter, log.parallel_filter->sample_rate_hz, log.has_qd, log.has_qdd, n_dof,
                   log.n_raw);
  }
  JointLogChunk chunk;
  Eigen::Index read = 0;           // source samples read
  const Eigen::Index end = log.first + log.n_raw;
  while (read < end && source.Next(std::min(kStreamBlockSamples, end - read), &chunk)) {
    JointLog& samples = chunk.samples;
    const Eigen::Index m = samples.t.size();
    const Eigen::Index skip = std::max<Eigen::Index>(0, log.first - read);  // before the window
    read += m;
    if (skip >= m) continue;
    auto rows = [&](Eigen::MatrixXd* x, Eigen::Index from, Eigen::Index count) {
      if (x->size() > 0) *x = x->middleRows(from, count).eval();
    };
    if (skip > 0) {
      samples.t = samples.t.segment(skip, m - skip).eval();
      for (Eigen::MatrixXd* x : {&samples.q, &samples.qd, &samples.qdd, &samples.tau}) rows(x, skip, m - skip);
    }
    if (filter) {
      filter->Push(samples, sink);
    } else {
      // Every decimation-th sample of the window, counted from its first.
      const Eigen::Index k = log.decimation, s0 = read - m + skip - log.first, count = samples.t.size();
      const Eigen::Index offset = (k - s0 % k) % k;
      if (k > 1) {
        const Eigen::Index kept = offset < count ? (count - offset + k - 1) / k : 0;
        JointLog out;
        out.t.resize(kept);
        for (Eigen::MatrixXd* x : {&out.q, &out.qd, &out.qdd, &out.tau}) x->resize(kept, n_dof);
        for (Eigen::Index i = 0; i < kept; ++i) {
          const Eigen::Index r = offset + i * k;
          out.t[i] = samples.t[r];
          out.q.row(i) = samples.q.row(r);
          out.qd.row(i) = samples.qd.row(r);
          out.qdd.row(i) = samples.qdd.row(r);
          out.tau.row(i) = samples.tau.row(r);
        }
        if (kept > 0) sink(out, (s0 + offset) / k);
      } else {
        sink(samples, s0);
      }
    }
    if (progress) progress->Update(read - log.first, log.n_raw);
  }
}

// The first pass over a source: its samples and those in the time window
// [t0, t1], the window's ends and its shortest and longest steps (uniform
// when all are within 1e-6 of the shortest: what ResampleJointLog calls
// uniform, without the median).
struct WindowScan {
  Eigen::Index n_total = 0, n = 0;  // samples in the log, in the window
  Eigen::Index first = 0;           // the window's first sample
  double t_first = 0.0, t_last = 0.0, w_first = 0.0, w_last = 0.0, min_step = INFINITY, max_step = 0.0;  // [s]
};

WindowScan ScanWindow(JointLogSource* source, double t0, double t1, const StreamObserver* observer) {
  WindowScan scan;
  JointLogChunk chunk;
  source->Rewind();
  double previous = 0.0;
  while (source->Next(kStreamBlockSamples, &chunk)) {
    if (observer && observer->stop && observer->stop->load()) throw StreamStopped();
    for (double t : chunk.samples.t) {
      if (scan.n_total == 0) scan.t_first = t;
      scan.t_last = t;
      ++scan.n_total;
      if (t < t0 || t > t1) continue;
      if (scan.n == 0) {
        scan.first = scan.n_total - 1;
        scan.w_first = t;
      } else {
        scan.min_step = std::min(scan.min_step, t - previous);
        scan.max_step = std::max(scan.max_step, t - previous);
      }
      previous = scan.w_last = t;
      ++scan.n;
    }
  }
  return scan;
}

// Irregular steps in the window: the window (out->first, out->n_raw samples
// of out->source) held whole and resampled onto a uniform grid, which
// becomes out->source; a gap is an error naming its line. The new window's
// ends in *w_first, *w_last.
void ResampleWindow(const std::string& path, const LogPreparationOptions& options, PreparedLog* out, double* w_first,
                    double* w_last) {
  const Eigen::Index n = out->n_raw;
  out->source->Rewind();
  RecordedJointLog recorded = ReadWholeLog(*out->source);
  const Eigen::Index last = out->first + n;
  JointLog& log = recorded.log;
  log.t = log.t.segment(out->first, n).eval();
  for (Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd, &log.tau}) {
    if (x->size() > 0) *x = x->middleRows(out->first, n).eval();
  }
  recorded.lines = std::vector<int>(recorded.lines.begin() + out->first, recorded.lines.begin() + last);
  RecordedJointLog uniform;
  const ResamplingSummary resampling = ResampleJointLog(log, {.max_gap_s = options.max_gap_s}, &uniform.log);
  if (resampling.status == ResamplingStatus::kGap) {
    const int line = recorded.lines[static_cast<size_t>(resampling.gap_sample)];
    throw std::invalid_argument(path + ":" + std::to_string(line) + ": column 't': " + resampling.BriefReport() +
                                "; split the log there or choose a time_window without it (max_gap_s sets the "
                                "bound)");
  }
  if (resampling.status == ResamplingStatus::kResampled) out->notes.push_back(path + ": " + resampling.BriefReport());
  const Eigen::Index m = uniform.log.n_samples();
  *w_first = uniform.log.t[0];
  *w_last = uniform.log.t[m - 1];
  uniform.lines.resize(static_cast<size_t>(m));
  for (Eigen::Index s = 0; s < m; ++s) uniform.lines[static_cast<size_t>(s)] = static_cast<int>(s);
  const bool tau_is_current = out->source->layout().tau_is_current;
  out->source = std::make_shared<RecordedJointLogSource>(std::move(uniform), path, tau_is_current);
  out->first = 0;
  out->n_raw = m;
}

// The second pass: out->log, the prepared log as held (every log_stride-th
// sample of out->n_samples), with a progress line on long logs.
void HoldPreparedLog(int n_dof, const std::string& path, const StreamObserver* observer, PreparedLog* out) {
  const Eigen::Index k = out->log_stride, m = (out->n_samples + k - 1) / k;
  JointLog& held = out->log;
  held.t.resize(m);
  for (Eigen::MatrixXd* x : {&held.q, &held.qd, &held.qdd, &held.tau}) x->resize(m, n_dof);
  ProgressLine progress(path + ": filtering", out->n_raw > kStreamBlockSamples, observer);
  StreamSamples(*out, [&](const JointLog& prepared, Eigen::Index s0) {
    for (Eigen::Index s = (s0 + k - 1) / k * k; s < s0 + prepared.n_samples(); s += k) {
      const Eigen::Index r = s - s0;
      held.t[s / k] = prepared.t[r];
      held.q.row(s / k) = prepared.q.row(r);
      held.qd.row(s / k) = prepared.qd.row(r);
      held.qdd.row(s / k) = prepared.qdd.row(r);
      held.tau.row(s / k) = prepared.tau.row(r);
    }
  }, &progress);
}

}  // namespace

PreparedLog PrepareJointLog(const std::string& path, const RobotModel& model, const LogPreparationOptions& options,
                            const StreamObserver* observer) {
  // Read one block ahead on another thread: parsing overlaps the filter and the fold.
  std::shared_ptr<JointLogSource> source =
      std::make_shared<PrefetchingJointLogSource>(OpenJointLog(path, model, options.format, options.torques));
  // A log description's time window, unless an option gives one too.
  const std::vector<double> described = source->layout().time_window;
  if (described.empty()) return PrepareJointLogSource(std::move(source), path, options, observer);
  if (!options.time_window.empty()) {
    throw std::invalid_argument(path + ": .time_window (" + Shortest(described[0]) + "," + Shortest(described[1]) +
                                ") and the option " + options.window_field + " (" + Shortest(options.time_window[0]) +
                                "," + Shortest(options.time_window[1]) + ") both give a time window: give it in one "
                                "place");
  }
  LogPreparationOptions windowed = options;
  windowed.time_window = described;
  windowed.window_field = ".time_window";
  return PrepareJointLogSource(std::move(source), path, windowed, observer);
}

PreparedLog PrepareRecordedJointLog(RecordedJointLog recorded, const std::string& path,
                                    const LogPreparationOptions& options) {
  std::unique_ptr<JointLogSource> source =
      std::make_unique<RecordedJointLogSource>(std::move(recorded), path, options.torques == TorqueColumns::kCurrents);
  // Held torques read as a file's are (OpenJointLog).
  if (options.format.torque_held) source = std::make_unique<internal::HeldTorqueSource>(std::move(source));
  return PrepareJointLogSource(std::move(source), path, options);
}

PreparedLog PrepareJointLogSource(std::shared_ptr<JointLogSource> source, const std::string& path,
                                  const LogPreparationOptions& options, const StreamObserver* observer) {
  PreparedLog out;
  const JointLogLayout& layout = source->layout();
  out.path = path;
  out.torque_held = options.format.torque_held;

  // First pass: the samples in the time window, its ends, and whether the
  // steps are uniform.
  const bool windowed = !options.time_window.empty();
  const double t0 = windowed ? options.time_window[0] : -INFINITY, t1 = windowed ? options.time_window[1] : INFINITY;
  const WindowScan scan = ScanWindow(source.get(), t0, t1, observer);
  const Eigen::Index n_total = scan.n_total;
  Eigen::Index n = scan.n;
  const double t_first = scan.t_first, t_last = scan.t_last;
  double w_first = scan.w_first, w_last = scan.w_last;
  out.first = scan.first;
  if (n_total == 0) throw std::invalid_argument(path + ": no samples");
  // The layout's notes and warnings after a whole pass (a source may add
  // some at its end, e.g. the degree check on the range of each joint).
  out.warnings = layout.warnings;
  out.notes = layout.notes;
  if (layout.torque_from_currents) out.notes.push_back(path + ": tau = K·i from the motor currents (drive_gains)");
  out.n_raw = n;
  out.source = source;
  out.has_qd = layout.has_qd;
  out.has_qdd = layout.has_qdd;

  // The time window.
  if (windowed) {
    const std::string option = options.window_field + " " + Shortest(t0) + "," + Shortest(t1);
    if (t0 < t_first || t1 > t_last) {
      throw std::invalid_argument(path + ": " + option + " is not inside the log, which covers t = " +
                                  Shortest(t_first) + " to " + Shortest(t_last) + " s");
    }
    constexpr Eigen::Index kMinSamples = 4;
    if (n < kMinSamples) {
      throw std::invalid_argument(path + ": " + option + " keeps " + std::to_string(n) + " samples, expected at least " +
                                  std::to_string(kMinSamples));
    }
    std::string label = options.window_field;  // time_window → "time window"
    std::replace(label.begin(), label.end(), '_', ' ');
    out.notes.push_back(path + ": " + label + " " + Shortest(t0) + "–" + Shortest(t1) + " s: " + std::to_string(n) +
                        " of " + std::to_string(n_total) + " samples");
  }
  // A log of more than max_samples prepared samples (at rate_hz [Hz]) is
  // refused before it is held, naming the window (and the decimation, when
  // decimation_helps: it acts before holding) that keeps it in bound.
  auto refuse_beyond_bound = [&](Eigen::Index n_prepared, double rate_hz, bool decimation_helps) {
    const Eigen::Index max = options.max_samples;
    if (max == 0 || n_prepared <= max) return;
    // A window of (max − 1) steps holds max samples, its ends included.
    std::string fix = "choose a " + options.window_field + " of at most " +
                      Format("%.6g", static_cast<double>(max - 1) / rate_hz) + " s (" + std::to_string(max) +
                      " samples at " + Format("%.6g", rate_hz) + " Hz)";
    if (decimation_helps) {  // ceil(n / k) <= max
      fix += ", or a filter.decimation of at least " + std::to_string((n + max - 1) / max);
    }
    throw std::invalid_argument(path + ": " + std::to_string(n_prepared) + " samples to hold whole, more than " +
                                std::to_string(max) + " (the bound that keeps memory from growing with the log); " +
                                fix);
  };
  auto hold = [&](Eigen::Index n_prepared) {
    out.n_samples = n_prepared;
    const Eigen::Index max = options.max_held_samples;
    out.log_stride = max > 0 ? std::max<Eigen::Index>(1, (n_prepared + max - 1) / max) : 1;
  };

  if (out.has_qd && out.has_qdd) {
    out.derivatives = "qd, qdd from the log";
    // Decimation keeps every k-th sample, as it does after filtering (no
    // filter here: the recorded signals are used as they are).
    const int k = options.filter.decimation;
    out.decimation = k;
    refuse_beyond_bound((n + k - 1) / k, static_cast<double>(n - 1) / (w_last - w_first) / k, true);
    hold((n + k - 1) / k);
    if (k > 1) {
      out.notes.push_back(path + ": decimation " + std::to_string(k) + ": one sample in " + std::to_string(k) +
                          " kept, " + std::to_string(out.n_samples) + " of " + std::to_string(n));
    }
  } else {
    // A uniform grid for the filter: irregular steps are resampled (the log
    // held whole for it), a gap is an error.
    if (n < 3) {
      throw std::invalid_argument(path + ": " + std::to_string(n) +
                                  " samples, too few to estimate qd, qdd by filtering");
    }
    refuse_beyond_bound(n, static_cast<double>(n - 1) / (w_last - w_first), false);  // before resampling holds it
    if (!(scan.max_step - scan.min_step <= ResamplingOptions{}.uniform_tolerance * scan.min_step)) {
      ResampleWindow(path, options, &out, &w_first, &w_last);
      n = out.n_raw;
    }
    const double rate_hz = static_cast<double>(n - 1) / (w_last - w_first);

    // Enough samples for the zero-phase filter, a cutoff the kept samples do
    // not alias, said in the user's terms.
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
    if (!(options.filter.cutoff_hz < 0.5 * rate_hz)) {
      throw std::invalid_argument(path + ": joint log: expected cutoff_hz < fs/(2·decimation) = " +
                                  Shortest(0.5 * rate_hz) + " Hz, got " + Shortest(options.filter.cutoff_hz) +
                                  " Hz (fs = " + Shortest(rate_hz) + " Hz)");
    }
    out.parallel_filter = ParallelFilter{options.filter, rate_hz};
    refuse_beyond_bound(n, rate_hz, false);  // decimation acts after filtering, on the samples held
    hold(n);
    if (const int k = options.filter.decimation; k > 1) {  // the equations kept (ParallelFilterKeptSamples)
      const Eigen::Index trim = ParallelFilterTrimSamples(options.filter, rate_hz);
      out.notes.push_back(path + ": decimation " + std::to_string(k) + " after filtering: one sample in " +
                          std::to_string(k) + " kept, " + std::to_string(std::max<Eigen::Index>(0, (n - 2 * trim + k - 1) / k)) +
                          " of " + std::to_string(n) + " (" + std::to_string(trim) +
                          " filter-transient samples dropped at each end)");
    }
    out.derivatives = out.has_qd ? "qd from the log (filtered), qdd from the filtered qd"
                    : out.has_qdd ? "qd from the filtered q, qdd from the log (filtered)"
                                  : "qd, qdd from the filtered q";
  }

  // Second pass: the prepared log as held (every log_stride-th sample).
  HoldPreparedLog(layout.n_dof, path, observer, &out);
  return out;
}

void StreamPreparedSamples(const PreparedLog& log, const StreamedLogFilter::Sink& sink, const std::string& activity,
                           const StreamObserver* observer) {
  ProgressLine progress(log.path + ": " + activity, log.n_raw > kStreamBlockSamples, observer);
  StreamSamples(log, sink, &progress);
}

}  // namespace idbench
