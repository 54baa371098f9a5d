// A RecordedJointLog held in memory seen as a JointLogSource, and the way
// back: every sample of a source gathered into one RecordedJointLog (for what
// needs the whole log at once: playback, plots, short logs).
#pragma once

#include "idbench/logs/joint_log_source.h"
#include "idbench/logs/recorded_joint_log.h"

namespace idbench {

// Hands out the samples of a log it owns. records are the log's lines.
class RecordedJointLogSource final : public JointLogSource {
 public:
  RecordedJointLogSource(RecordedJointLog log, std::string source, bool tau_is_current = false);
  const JointLogLayout& layout() const override { return layout_; }
  bool Next(Eigen::Index max_samples, JointLogChunk* chunk) override;
  void Rewind() override { next_ = 0; }

 private:
  RecordedJointLog log_;
  JointLogLayout layout_;
  Eigen::Index next_ = 0;
};

// Every remaining sample of `source` (from where it stands) in one log, read
// in chunks of chunk_samples; lines are the chunks' records; notes and
// warnings are the layout's after the last chunk.
RecordedJointLog ReadWholeLog(JointLogSource& source, Eigen::Index chunk_samples = 65536);

}  // namespace idbench
