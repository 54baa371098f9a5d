// Constant joint acceleration from a start pose: the paper's motion.
//   q(t) = q0 + qd0 t + ½ qdd t²
#pragma once

#include "idbench/engine/trajectory.h"

namespace idbench {

class ConstantAccelerationTrajectory final : public Trajectory {
 public:
  // Throws std::invalid_argument on size mismatch or duration <= 0.
  ConstantAccelerationTrajectory(Eigen::VectorXd q0, Eigen::VectorXd qd0, Eigen::VectorXd qdd,
                                 double duration);

  int n_dof() const override { return static_cast<int>(q0_.size()); }
  double duration() const override { return duration_; }
  void Evaluate(double t, JointState* state) const override;
  const Eigen::VectorXd& q0() const { return q0_; }    // start pose [rad] (n_dof)
  const Eigen::VectorXd& qd0() const { return qd0_; }  // start velocity [rad/s] (n_dof)
  const Eigen::VectorXd& qdd() const { return qdd_; }  // acceleration [rad/s²] (n_dof)

 private:
  Eigen::VectorXd q0_, qd0_, qdd_;
  double duration_;
};

}  // namespace idbench
