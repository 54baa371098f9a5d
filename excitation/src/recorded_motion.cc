#include "idbench/excitation/recorded_motion.h"

#include <algorithm>
#include <stdexcept>

namespace idbench {

void RecordedMotion::Evaluate(double t, JointState* state) const {
  const double* begin = log_.t.data();
  const Eigen::Index n = log_.n_samples();
  const double at = std::clamp(log_.t[0] + t, log_.t[0], log_.t[n - 1]);
  const Eigen::Index i = std::clamp<Eigen::Index>((std::upper_bound(begin, begin + n, at) - begin) - 1, 0, n - 2);
  const double w = (at - log_.t[i]) / (log_.t[i + 1] - log_.t[i]);
  state->q = ((1.0 - w) * log_.q.row(i) + w * log_.q.row(i + 1)).transpose();
  state->qd = ((1.0 - w) * log_.qd.row(i) + w * log_.qd.row(i + 1)).transpose();
  state->qdd = ((1.0 - w) * log_.qdd.row(i) + w * log_.qdd.row(i + 1)).transpose();
}

std::unique_ptr<RecordedMotion> MakeRecordedMotion(const PreparedLog& prepared, const std::string& path) {
  const JointLog& log = prepared.log;
  double trim = 0.0;  // [s] at both ends
  if (prepared.parallel_filter) {
    trim = static_cast<double>(ParallelFilterTrimSamples(prepared.parallel_filter->filter,
                                                         prepared.parallel_filter->sample_rate_hz)) /
           prepared.parallel_filter->sample_rate_hz;
  }
  const double t0 = log.t[0] + trim - 1e-9, t1 = log.t[log.n_samples() - 1] - trim + 1e-9;
  const Eigen::Index first = (log.t.array() < t0).count(), end = (log.t.array() <= t1).count();
  if (end - first < 2) {
    throw std::invalid_argument(path + ": " + std::to_string(std::max<Eigen::Index>(end - first, 0)) +
                                " samples left after the filter's end transients; record a longer log");
  }
  JointLog kept;
  kept.t = log.t.segment(first, end - first);
  kept.q = log.q.middleRows(first, end - first);
  kept.qd = log.qd.middleRows(first, end - first);
  kept.qdd = log.qdd.middleRows(first, end - first);
  const double duration = kept.t[kept.n_samples() - 1] - kept.t[0];
  return std::make_unique<RecordedMotion>(std::move(kept), duration);
}

}  // namespace idbench
