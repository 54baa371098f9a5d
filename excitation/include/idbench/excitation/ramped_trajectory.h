// A motion framed by rest-to-rest ramps, as a robot runs it: from the home
// pose at rest into the motion, the motion, then out of it back to the home
// pose at rest. With the motion m continued outside [0, D] (see below), e =
// m − home and σ(s) = 10s³ − 15s⁴ + 6s⁵ (σ, σ', σ'' are 0 at s = 0 and
// σ = 1, σ' = σ'' = 0 at s = 1):
//
//   t ∈ [0, T_r]:              q = home + σ(t/T_r) · e(t − T_r)
//   t ∈ [T_r, T_r + D]:        q = m(t − T_r)
//   t ∈ [T_r + D, D + 2T_r]:   q = home + σ(1 − (t − T_r − D)/T_r) · e(t − T_r)
//
// so q, qd and qdd are continuous, zero velocity and acceleration at both
// ends. Each joint stays between the home and the motion (a convex
// combination), and qd = σ̇e + σṁ, qdd = σ̈e + 2σ̇ṁ + σm̈ tend to the motion's
// own as T_r grows: a ramp too short is what exceeds a limit.
// Continuation: an end where the motion is at rest (qd = qdd = 0) holds its
// pose, which makes that ramp the rest-to-rest quintic over Δ = |m − home|
// (peaks |qd| = 15/8·Δ/T_r, |qdd| = 10/√3·Δ/T_r²); at an end in motion the
// motion's own formula is evaluated beyond it (a Fourier series: its
// periodic continuation, the motion the robot would have run before).
// With T_r = 0 it is the motion itself.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "idbench/engine/trajectory.h"

namespace idbench {

class RampedTrajectory final : public Trajectory {
 public:
  // home [rad] (n_dof of the motion), ramp_seconds >= 0 and finite. Throws
  // std::invalid_argument otherwise.
  RampedTrajectory(std::shared_ptr<const Trajectory> motion, Eigen::VectorXd home, double ramp_seconds);

  int n_dof() const override { return motion_->n_dof(); }
  double duration() const override { return motion_->duration() + 2.0 * ramp_seconds_; }
  void Evaluate(double t, JointState* state) const override;

  const Trajectory& motion() const { return *motion_; }
  const Eigen::VectorXd& home() const { return home_; }
  double ramp_seconds() const { return ramp_seconds_; }

 private:
  std::shared_ptr<const Trajectory> motion_;
  Eigen::VectorXd home_;
  double ramp_seconds_;
  // The motion at time t of its own clock, continued outside [0, D].
  void Continued(double t, JointState* state) const;

  JointState start_, end_;           // the motion's state at 0 and at its duration
  bool start_at_rest_ = false, end_at_rest_ = false;
};

}  // namespace idbench
