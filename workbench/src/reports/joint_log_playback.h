// A recorded joint log as a trajectory, to draw the poses of an experiment.
#pragma once

#include <algorithm>

#include "idbench/engine/measurements.h"
#include "idbench/engine/trajectory.h"

namespace idbench::internal {

// A joint log played back as a trajectory (the nearest sample at or before t),
// to draw the poses of a recorded experiment.
class JointLogPlayback final : public Trajectory {
 public:
  explicit JointLogPlayback(const JointLog& log) : log_(log) {}
  int n_dof() const override { return log_.n_dof(); }
  double duration() const override { return log_.t[log_.n_samples() - 1] - log_.t[0]; }
  void Evaluate(double t, JointState* state) const override {
    const double* begin = log_.t.data();
    const auto it = std::upper_bound(begin, begin + log_.n_samples(), log_.t[0] + t + 1e-12);
    const Eigen::Index i = std::max<Eigen::Index>(0, (it - begin) - 1);
    state->q = log_.q.row(i).transpose();
    state->qd.setZero(), state->qdd.setZero();
  }

 private:
  const JointLog& log_;
};

}  // namespace idbench::internal
