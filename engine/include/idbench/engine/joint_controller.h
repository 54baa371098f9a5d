// A joint-space PID controller as a robot runs it: sampled at its own period
// (zero-order hold between samples), acting on the MEASURED positions (the
// encoders' noise and quantum: what makes a closed-loop log's regressor
// correlated with the noise), with torque saturation and an optional model
// feed-forward along the reference.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"

namespace idbench {

struct JointControllerOptions {
  // Gains, one value for every joint or one per joint.
  std::vector<double> kp;       // [N m/rad]
  std::vector<double> kd;       // [N m s/rad]
  std::vector<double> ki;       // [N m/(rad s)]; empty = 0
  std::vector<double> tau_max;  // |τ| limit [N m]; empty = none
  // Adds τ_ff = RNEA(q_ref, q̇_ref, q̈_ref) + the joints' friction and rotor
  // terms of the controller's model (its nominal model, not the plant).
  bool model_feedforward = false;
  static constexpr double kMaxGain = 1e12;  // a gain beyond is a typo, not a controller

  // *why names the field ("kp", "tau_max") and what is wrong with it.
  bool IsValid(int n_dof, std::string* why) const;
};

class JointController {
 public:
  // sample_period [s] > 0; `model` gives n_dof and the feed-forward (kept
  // by reference: it must outlive the controller). Throws
  // std::invalid_argument naming the field when the options are not valid.
  JointController(const JointControllerOptions& options, const RobotModel& model, double sample_period);

  // Back to the state before the first sample (no integral, no history).
  void Reset();

  // The torque commanded at the sample at time t [s], held to t + T, from
  // the reference and the measured positions (n_dof): with e = q_ref(t) −
  // q_measured,
  //   τ = τ_ff(t + T/2) + Kp e + Kd (e_k − e_{k−1})/T + Ki Σ T e,   clamped to ±τ_max,
  // the derivative 0 at the first sample; the integral stops growing on a
  // joint while its torque is clamped (anti-windup). The feed-forward is the
  // model's torque at the middle of the hold (t clamped to the reference's
  // duration): held at its start, it would lag by T/2, a tracking error of
  // ~T/2·|q̇| (puma560 without Coulomb friction at 1 kHz, measured: 1.5e-4
  // rad from the start of the hold, 7.7e-8 from its middle).
  // Throws std::invalid_argument on sizes other than n_dof.
  void Command(const Trajectory& reference, double t, const Eigen::VectorXd& q_measured, Eigen::VectorXd* tau);

  int n_dof() const { return model_.n_dof(); }

 private:
  const RobotModel& model_;
  double period_;
  bool feedforward_;
  Eigen::VectorXd kp_, kd_, ki_, tau_max_;  // per joint; tau_max +∞ when none
  Eigen::VectorXd integral_, error_, previous_error_;
  bool started_ = false;
  RobotData data_;
  JointState reference_, feedforward_state_;
};

}  // namespace idbench
