#include "idbench/gui/log_envelope.h"

#include <stdexcept>
#include <string>

namespace idbench::gui {

LogEnvelope::LogEnvelope(Eigen::Index max_buckets) : max_buckets_(max_buckets) {
  if (max_buckets < 1) throw std::invalid_argument("max_buckets: expected >= 1, got " + std::to_string(max_buckets));
}

void LogEnvelope::Add(const Eigen::VectorXd& t, const Eigen::MatrixXd& values) {
  if (values.rows() != t.size()) {
    throw std::invalid_argument("values: expected " + std::to_string(t.size()) + " rows (one per time), got " +
                                std::to_string(values.rows()));
  }
  if (t.size() == 0) return;
  if (n_samples_ == 0) {  // the fixed workspace, once
    const Eigen::Index capacity = 2 * max_buckets_;
    t_begin_.resize(capacity), t_end_.resize(capacity), count_.resize(capacity);
    min_.resize(capacity, values.cols()), max_.resize(capacity, values.cols()), sum_.resize(capacity, values.cols());
  } else if (values.cols() != n_channels()) {
    throw std::invalid_argument("values: expected " + std::to_string(n_channels()) + " columns (channels), got " +
                                std::to_string(values.cols()));
  }
  for (Eigen::Index i = 0; i < t.size(); ++i, ++n_samples_) {
    // A new bucket when the last is full; pairs merge first when none is free.
    if (n_buckets_ == 0 || count_[n_buckets_ - 1] == samples_per_bucket_) {
      if (n_buckets_ == 2 * max_buckets_) MergePairs();
      const Eigen::Index k = n_buckets_++;
      t_begin_[k] = t_end_[k] = t[i];
      count_[k] = 1;
      min_.row(k) = max_.row(k) = sum_.row(k) = values.row(i);
      continue;
    }
    const Eigen::Index k = n_buckets_ - 1;
    t_end_[k] = t[i];
    ++count_[k];
    min_.row(k) = min_.row(k).cwiseMin(values.row(i));
    max_.row(k) = max_.row(k).cwiseMax(values.row(i));
    sum_.row(k) += values.row(i);
  }
}

// 2·max_buckets full buckets → max_buckets, each covering two.
void LogEnvelope::MergePairs() {
  for (Eigen::Index r = 0; r < max_buckets_; ++r) {
    const Eigen::Index a = 2 * r, b = 2 * r + 1;
    t_begin_[r] = t_begin_[a];
    t_end_[r] = t_end_[b];
    count_[r] = count_[a] + count_[b];
    min_.row(r) = min_.row(a).cwiseMin(min_.row(b));
    max_.row(r) = max_.row(a).cwiseMax(max_.row(b));
    sum_.row(r) = sum_.row(a) + sum_.row(b);
  }
  n_buckets_ = max_buckets_;
  samples_per_bucket_ *= 2;
}

Eigen::MatrixXd LogEnvelope::Mean() const {
  Eigen::MatrixXd mean = sum_.topRows(n_buckets_);
  for (Eigen::Index k = 0; k < n_buckets_; ++k) mean.row(k) /= static_cast<double>(count_[k]);
  return mean;
}

bool FoldJointPositions(JointLogSource& source, const std::atomic<bool>& stop, LogEnvelope* envelope) {
  JointLogChunk chunk;
  while (!stop && source.Next(4096, &chunk)) envelope->Add(chunk.samples.t, chunk.samples.q);
  return !stop;
}

}  // namespace idbench::gui
