#include "idbench/excitation/ramped_trajectory.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace idbench {
namespace {

bool AtRest(const JointState& state) { return state.qd.isZero(0.0) && state.qdd.isZero(0.0); }

}  // namespace

RampedTrajectory::RampedTrajectory(std::shared_ptr<const Trajectory> motion, Eigen::VectorXd home, double ramp_seconds)
    : motion_(std::move(motion)), home_(std::move(home)), ramp_seconds_(ramp_seconds) {
  if (!motion_) throw std::invalid_argument("RampedTrajectory: expected a motion, got none");
  if (home_.size() != motion_->n_dof()) {
    throw std::invalid_argument("RampedTrajectory: expected a home pose of " + std::to_string(motion_->n_dof()) +
                                " joints, got " + std::to_string(home_.size()));
  }
  if (!(ramp_seconds_ >= 0.0) || !std::isfinite(ramp_seconds_)) {
    throw std::invalid_argument("RampedTrajectory: expected a ramp duration >= 0 s, got " + std::to_string(ramp_seconds_));
  }
  start_ = motion_->At(0.0);
  end_ = motion_->At(motion_->duration());
  start_at_rest_ = AtRest(start_);
  end_at_rest_ = AtRest(end_);
}

void RampedTrajectory::Continued(double t, JointState* state) const {
  const bool hold = t < 0.0 ? start_at_rest_ : end_at_rest_;
  if (hold) {
    *state = t < 0.0 ? start_ : end_;
  } else {
    motion_->Evaluate(t, state);
  }
}

void RampedTrajectory::Evaluate(double t, JointState* state) const {
  const double T = ramp_seconds_, D = motion_->duration();
  if (T == 0.0 || (t >= T && t <= T + D)) {
    motion_->Evaluate(t - T, state);
    return;
  }
  // The blend weight σ and its time derivatives: rising over the first ramp,
  // falling over the last (s runs backwards there).
  const bool first = t < T;
  const double s = first ? t / T : 1.0 - (t - T - D) / T, ds_dt = first ? 1.0 / T : -1.0 / T;
  const double sigma = s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
  const double sigma_t = 30.0 * s * s * (1.0 - s) * (1.0 - s) * ds_dt;
  const double sigma_tt = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) * ds_dt * ds_dt;
  Continued(t - T, state);
  const Eigen::VectorXd e = state->q - home_;
  state->qdd = sigma_tt * e + 2.0 * sigma_t * state->qd + sigma * state->qdd;
  state->qd = sigma_t * e + sigma * state->qd;
  state->q = home_ + sigma * e;
}

}  // namespace idbench
