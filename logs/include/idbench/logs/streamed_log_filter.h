// ProcessJointLog (without decimation or trimming, τ left unfiltered) on a
// long log handed over in chunks (issue 24): the recorded q (qd, qdd)
// zero-phase filtered in overlapping windows (OverlapWindows,
// FiltFiltWindow) and differentiated where not recorded. Holds
// O(block + 2·margin) samples; the output equals ProcessJointLog's on the
// whole log to the filter's 1e-12 settling (exactly when one window covers
// the log).
#pragma once

#include <functional>
#include <optional>

#include "idbench/engine/measurements.h"
#include "idbench/logs/overlap_windows.h"
#include "idbench/logs/signal_filter.h"

namespace idbench {

// Samples per processing block of the streamed stages: the bound on what a
// stage holds beyond its two filter margins (1442 samples each at the
// defaults). 8192 samples of a 7-joint arm's per-joint regressor columns
// (~200 doubles a sample) are 13 MB.
inline constexpr Eigen::Index kStreamBlockSamples = 8192;

class StreamedLogFilter {
 public:
  // Prepared samples [s0, s0 + prepared.n_samples()) with t, q, qd, qdd and
  // τ (as recorded).
  using Sink = std::function<void(const JointLog& prepared, Eigen::Index s0)>;

  // options: order and cutoff_hz (decimation and trim_s are the caller's);
  // the log has n_samples samples at sample_rate_hz, with qd / qdd recorded
  // as has_qd / has_qdd (not both). Throws std::invalid_argument for invalid
  // options, a cutoff at or above fs/2, or fewer samples than FiltFilt needs.
  StreamedLogFilter(const LogFilterOptions& options, double sample_rate_hz, bool has_qd, bool has_qdd, int n_dof,
                    Eigen::Index n_samples, Eigen::Index block = kStreamBlockSamples);

  // The log's next samples, in order (t, q, the recorded qd/qdd, tau); calls
  // `sink` for every block of prepared samples now final. Throws
  // std::invalid_argument on a shape mismatch or more samples than announced.
  void Push(const JointLog& samples, const Sink& sink);
  bool done() const { return windows_->done(); }

 private:
  void Window(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0, Eigen::Index o1,
              const Sink& sink) const;

  SosMatrix sos_;
  double dt_;
  bool has_qd_, has_qdd_;
  int n_dof_;
  Eigen::Index n_samples_;
  std::optional<OverlapWindows> windows_;
  Eigen::MatrixXd input_;  // workspace
};

}  // namespace idbench
