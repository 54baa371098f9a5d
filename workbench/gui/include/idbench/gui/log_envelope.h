// The envelope of a joint log for its plot, folded from the log's stream in
// bounded memory: consecutive samples are gathered into time buckets, each
// holding its time range and, per channel, the minimum, maximum and mean of
// its samples. Unlike keeping every k-th sample, nothing between the kept
// points is lost: a motion faster than the buckets shows as a band between
// min and max, never as a slower motion that is not in the log (aliasing).
#pragma once

#include <atomic>

#include <Eigen/Core>

#include "idbench/logs/joint_log_source.h"

namespace idbench::gui {

class LogEnvelope {
 public:
  // Holds between max_buckets and 2·max_buckets buckets once the log has
  // that many samples (each one sample to begin with). Memory is fixed at the
  // first sample: 2·max_buckets × (3 + 3·n_channels) doubles. Throws
  // std::invalid_argument for max_buckets < 1.
  explicit LogEnvelope(Eigen::Index max_buckets = 2000);

  // Folds samples in time order: t (n) [s], values (n × n_channels). Every
  // bucket but the last holds samples_per_bucket() samples; when 2·max_buckets
  // full buckets are held and another sample comes, neighbours merge pairwise
  // (min of mins, max of maxes, summed means) and the bucket size doubles.
  // Throws std::invalid_argument when the channel count changes or t and
  // values differ in length.
  void Add(const Eigen::VectorXd& t, const Eigen::MatrixXd& values);

  Eigen::Index n_buckets() const { return n_buckets_; }
  Eigen::Index n_channels() const { return min_.cols(); }
  Eigen::Index max_buckets() const { return max_buckets_; }
  long long n_samples() const { return n_samples_; }
  long long samples_per_bucket() const { return samples_per_bucket_; }

  // Bucket k (0 <= k < n_buckets()): its first and last sample's time [s],
  // its sample count, and per channel the min, max and mean of its samples.
  double t_begin(Eigen::Index k) const { return t_begin_[k]; }
  double t_end(Eigen::Index k) const { return t_end_[k]; }
  long long count(Eigen::Index k) const { return count_[k]; }
  auto min() const { return min_.topRows(n_buckets_); }   // (n_buckets × n_channels)
  auto max() const { return max_.topRows(n_buckets_); }   // (n_buckets × n_channels)
  Eigen::MatrixXd Mean() const;                            // (n_buckets × n_channels)

 private:
  void MergePairs();

  Eigen::Index max_buckets_;
  Eigen::Index n_buckets_ = 0;
  long long n_samples_ = 0;
  long long samples_per_bucket_ = 1;
  Eigen::VectorXd t_begin_, t_end_;
  Eigen::Matrix<long long, Eigen::Dynamic, 1> count_;
  Eigen::MatrixXd min_, max_, sum_;  // (2·max_buckets × n_channels)
};

// Reads a log's joint positions [rad] into *envelope, chunk by chunk. False
// when *stop was set before the end (the envelope then holds a prefix).
// Throws what the source throws for bad data.
bool FoldJointPositions(JointLogSource& source, const std::atomic<bool>& stop, LogEnvelope* envelope);

}  // namespace idbench::gui
