// Limits on the motor side of a transmission (transmission.h), for the
// excitation design: each motor's velocity |θ̇m| with θ̇m = A·q̇ (linear in
// the design's unknowns, as the joint velocities) and torque |τm| with
// τm = A⁻ᵀ·τ (τ the joint torque, by virtual work).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/transmission.h"

namespace idbench {

struct ActuatorLimit {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double qd_max = kInf;   // [rad/s of the motor] bound on |θ̇m|; inf: none
  double tau_max = kInf;  // [N m] bound on |τm|; inf: none
};

struct ActuatorLimits {
  Transmission transmission;          // A = actuator_from_joint (joint_offset unused)
  std::vector<ActuatorLimit> motors;  // one per motor (n_dof), in A's row order; empty: none

  bool empty() const { return motors.empty(); }
  // Throws std::invalid_argument naming the field: "transmission: …" for a
  // transmission invalid for n_dof, "actuators: expected 6 entries (one per
  // motor), got 5", "actuators[5].qd_max: must be > 0, got -1".
  void Check(int n_dof) const;
  // A⁻ᵀ (n_dof × n_dof): τm = A⁻ᵀ·τ.
  Eigen::MatrixXd MotorTorqueFromJoint() const;
  // The joints motor k (0-based) drives, the non-zeros of A's row k: "joint_5, joint_6".
  std::string DrivenJoints(const RobotModel& model, int motor) const;
};

}  // namespace idbench
