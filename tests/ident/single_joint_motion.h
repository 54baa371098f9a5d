// A motion of one joint, the others held at a pose: what a user records when
// only the wrist turns, and a motion that leaves some of a payload's
// parameters unseen.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "idbench/engine/trajectory.h"

namespace idbench::testing {

// Joint `joint` follows q = pose + 1.5 sin(ωt) + 0.8 sin(3ωt) (ω = 2π · 0.2 Hz),
// every other joint stays at `pose`.
class SingleJointMotion : public Trajectory {
 public:
  SingleJointMotion(Eigen::VectorXd pose, int joint, double duration)
      : pose_(std::move(pose)), joint_(joint), duration_(duration) {}
  int n_dof() const override { return static_cast<int>(pose_.size()); }
  double duration() const override { return duration_; }
  void Evaluate(double t, JointState* state) const override {
    const double w = 2.0 * M_PI * 0.2;
    state->q = pose_;
    state->qd.setZero();
    state->qdd.setZero();
    state->q[joint_] += 1.5 * std::sin(w * t) + 0.8 * std::sin(3 * w * t);
    state->qd[joint_] = 1.5 * w * std::cos(w * t) + 2.4 * w * std::cos(3 * w * t);
    state->qdd[joint_] = -1.5 * w * w * std::sin(w * t) - 7.2 * w * w * std::sin(3 * w * t);
  }

 private:
  Eigen::VectorXd pose_;
  int joint_;
  double duration_;
};

}  // namespace idbench::testing
