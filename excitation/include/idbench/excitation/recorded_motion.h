// A recorded log as the motion it ran (compare ranks recorded logs beside
// designed motions by simulating them): q, qd and qdd each interpolated
// linearly between the recorded samples, exact at every sample. Not one C²
// curve through all three (SampledTrajectory): a recorded qdd is rarely the
// second derivative of the recorded q (filtered apart, a sample's lag), and a
// curve forced through both amplifies the mismatch by 1/h² between samples.
#pragma once

#include <memory>
#include <string>

#include "idbench/engine/measurements.h"
#include "idbench/engine/trajectory.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

class RecordedMotion final : public Trajectory {
 public:
  // log: t, q, qd, qdd of ≥ 2 samples, t increasing. Time runs from the first
  // sample; `duration` (≤ the log's span) may cut the end.
  RecordedMotion(JointLog log, double duration) : log_(std::move(log)), duration_(duration) {}
  int n_dof() const override { return log_.n_dof(); }
  double duration() const override { return duration_; }
  void Evaluate(double t, JointState* state) const override;
  // Ends the motion at `duration` [s] from the first sample (a simulation's grid).
  void Cut(double duration) { duration_ = duration; }

 private:
  JointLog log_;
  double duration_;
};

// The motion of a prepared log (PrepareJointLog: read, resampled, qd and qdd
// estimated), with the filter's end transients dropped at both ends
// (ParallelFilterTrimSamples) where it was filtered. Throws
// std::invalid_argument naming `path` when fewer than 2 samples remain.
std::unique_ptr<RecordedMotion> MakeRecordedMotion(const PreparedLog& prepared, const std::string& path);

}  // namespace idbench
