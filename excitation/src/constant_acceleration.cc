#include "idbench/excitation/constant_acceleration.h"

#include <stdexcept>
#include <string>

namespace idbench {

ConstantAccelerationTrajectory::ConstantAccelerationTrajectory(Eigen::VectorXd q0, Eigen::VectorXd qd0,
                                                               Eigen::VectorXd qdd, double duration)
    : q0_(std::move(q0)), qd0_(std::move(qd0)), qdd_(std::move(qdd)), duration_(duration) {
  if (qd0_.size() != q0_.size() || qdd_.size() != q0_.size()) {
    throw std::invalid_argument("constant-acceleration trajectory: expected " + std::to_string(q0_.size()) +
                                " entries in qd0 and qdd, got " + std::to_string(qd0_.size()) + " and " +
                                std::to_string(qdd_.size()));
  }
  if (!(duration_ > 0.0)) throw std::invalid_argument("constant-acceleration trajectory: duration must be > 0");
}

void ConstantAccelerationTrajectory::Evaluate(double t, JointState* state) const {
  state->q = q0_ + qd0_ * t + 0.5 * qdd_ * t * t;
  state->qd = qd0_ + qdd_ * t;
  state->qdd = qdd_;
}

}  // namespace idbench
