#include "idbench/logs/prefetching_joint_log_source.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace idbench {

PrefetchingJointLogSource::PrefetchingJointLogSource(std::unique_ptr<JointLogSource> source,
                                                     Eigen::Index block_samples)
    : source_(std::move(source)), block_samples_(block_samples) {
  if (!source_) throw std::invalid_argument("PrefetchingJointLogSource: no source");
  if (block_samples_ < 1) throw std::invalid_argument("PrefetchingJointLogSource: block_samples must be at least 1");
}

PrefetchingJointLogSource::~PrefetchingJointLogSource() { Wait(); }

void PrefetchingJointLogSource::Wait() const {
  if (pending_.valid()) pending_.wait();
}

const JointLogLayout& PrefetchingJointLogSource::layout() const {
  Wait();
  return source_->layout();
}

void PrefetchingJointLogSource::StartRead() {
  pending_ = std::async(std::launch::async, [this] { return source_->Next(block_samples_, &next_); });
}

bool PrefetchingJointLogSource::Next(Eigen::Index max_samples, JointLogChunk* chunk) {
  if (max_samples < 1) throw std::invalid_argument("JointLogSource::Next: max_samples must be at least 1");
  if (cursor_ == current_.samples.t.size()) {
    // The block handed out: the next one (read ahead, or now), and the one after it started.
    bool got = false;
    if (!ended_) {
      if (!pending_.valid()) StartRead();
      got = pending_.get();  // rethrows the read's error
    }
    if (!got) {
      ended_ = true;
      *chunk = JointLogChunk();
      chunk->samples.q.resize(0, source_->layout().n_dof);
      return false;
    }
    std::swap(current_, next_);
    cursor_ = 0;
    StartRead();
  }
  // Up to max_samples of the block, from the cursor.
  const JointLog& from = current_.samples;
  const Eigen::Index m = std::min(max_samples, from.t.size() - cursor_);
  JointLog& to = chunk->samples;
  to.t = from.t.segment(cursor_, m);
  auto rows = [&](const Eigen::MatrixXd& x, Eigen::MatrixXd* y) {
    if (x.size() > 0) *y = x.middleRows(cursor_, m);
    else y->resize(0, 0);
  };
  rows(from.q, &to.q);
  rows(from.qd, &to.qd);
  rows(from.qdd, &to.qdd);
  rows(from.tau, &to.tau);
  chunk->records.assign(current_.records.begin() + cursor_, current_.records.begin() + cursor_ + m);
  cursor_ += m;
  return true;
}

void PrefetchingJointLogSource::Rewind() {
  // A read in flight is dropped (its error too: the next pass meets it again).
  if (pending_.valid()) {
    try {
      pending_.get();
    } catch (...) {
    }
  }
  source_->Rewind();
  current_ = JointLogChunk();
  cursor_ = 0;
  ended_ = false;
}

}  // namespace idbench
