// A JointLogSource that reads its source one block ahead on another thread,
// so that parsing the next block (a CSV's numbers, a bag's messages) runs
// while the caller works on this one. The caller sees the source's samples,
// chunking, errors and layout exactly as without it: a read that throws is
// rethrown when the caller asks for the samples it stopped at.
#pragma once

#include <future>
#include <memory>

#include "idbench/logs/joint_log_source.h"

namespace idbench {

class PrefetchingJointLogSource final : public JointLogSource {
 public:
  // Reads `source` in blocks of block_samples (>= 1) samples.
  explicit PrefetchingJointLogSource(std::unique_ptr<JointLogSource> source, Eigen::Index block_samples = 8192);
  ~PrefetchingJointLogSource() override;
  PrefetchingJointLogSource(const PrefetchingJointLogSource&) = delete;
  PrefetchingJointLogSource& operator=(const PrefetchingJointLogSource&) = delete;

  // The source's layout, once the read in flight (which may add warnings at
  // the end of the log) has finished.
  const JointLogLayout& layout() const override;
  bool Next(Eigen::Index max_samples, JointLogChunk* chunk) override;
  void Rewind() override;

 private:
  void StartRead();
  void Wait() const;

  std::unique_ptr<JointLogSource> source_;
  Eigen::Index block_samples_;
  mutable std::future<bool> pending_;  // the read into next_, when one is in flight
  JointLogChunk next_;                 // what the read in flight fills
  JointLogChunk current_;              // the block being handed out, from cursor_
  Eigen::Index cursor_ = 0;
  bool ended_ = false;                 // the source said it has no more samples
};

}  // namespace idbench
