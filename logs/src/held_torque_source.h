// A log whose torques are commands held from their sample to the next
// (zero-order hold, as a controller applies them): read as the torque the
// motion saw around each sample, (τ_{k−1} + τ_k)/2, the mean of the two holds
// that meet there. The motion's accelerations estimated from q at t_k (or
// recorded there as a smooth signal's) average the torque on both sides of
// t_k; a held τ_k alone acts on the half sample after it, and a fit that
// pairs it with t_k is off by half a sample (on a noise-free closed-loop log
// read as t, q, τ: 0.8 % parameter error instead of the filter's ~1e-5). The
// first sample keeps its own torque.
#pragma once

#include <memory>

#include "idbench/logs/joint_log_source.h"

namespace idbench::internal {

class HeldTorqueSource final : public JointLogSource {
 public:
  explicit HeldTorqueSource(std::unique_ptr<JointLogSource> source);
  const JointLogLayout& layout() const override;  // the source's, with a note saying so
  bool Next(Eigen::Index max_samples, JointLogChunk* chunk) override;
  void Rewind() override;

 private:
  std::unique_ptr<JointLogSource> source_;
  mutable JointLogLayout layout_;
  Eigen::RowVectorXd previous_;  // the last sample's torque as read (empty before the first)
};

}  // namespace idbench::internal
