// A motion given by samples (a trajectory file, a controller's set points),
// interpolated so that q, qd and qdd are continuous (C²):
//  - with qd and qdd given at the samples: quintic Hermite on each interval,
//    which passes through q, qd and qdd at every sample;
//  - with q alone: the natural cubic spline (qdd = 0 at the first and last
//    sample, which suits motions that start and end at rest), through q.
// Either way each interval is one quintic through the knots' (q, qd, qdd).
// Time is shifted so that the first sample is at t = 0; duration = last − first.
// Outside [0, duration] the end intervals' polynomials are extended.
#pragma once

#include <vector>

#include "idbench/engine/trajectory.h"

namespace idbench {

class SampledTrajectory final : public Trajectory {
 public:
  // t: sample times [s] (n_samples >= 2), strictly increasing; q: positions
  // [rad] (n_dof × n_samples); qd [rad/s], qdd [rad/s²]: both empty or both
  // n_dof × n_samples. Throws std::invalid_argument otherwise ("expected X, got Y").
  SampledTrajectory(Eigen::VectorXd t, Eigen::MatrixXd q, Eigen::MatrixXd qd = {}, Eigen::MatrixXd qdd = {});

  int n_dof() const override { return static_cast<int>(q_.rows()); }
  int n_samples() const { return static_cast<int>(t_.size()); }
  double duration() const override { return t_[t_.size() - 1]; }
  void Evaluate(double t, JointState* state) const override;

  // The knots after interpolation: times from 0 [s] (n_samples), and q, qd, qdd
  // at them (n_dof × n_samples; qd, qdd from the spline when not given).
  const Eigen::VectorXd& t() const { return t_; }
  const Eigen::MatrixXd& q() const { return q_; }
  const Eigen::MatrixXd& qd() const { return qd_; }
  const Eigen::MatrixXd& qdd() const { return qdd_; }

 private:
  Eigen::VectorXd t_;
  Eigen::MatrixXd q_, qd_, qdd_;
};

}  // namespace idbench
