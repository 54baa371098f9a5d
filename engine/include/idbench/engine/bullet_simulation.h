// Bullet (btMultiBody, double precision) simulation of a RobotModel with a
// fixed base, driven by joint torques, with joint feedback: the wrench every
// hinge transmits. Bullet types never leave this module (pimpl).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

enum class JointFeedbackMode {
  // Bullet 3.24's stock btMultiBodyJointFeedback. It re-runs the articulated
  // body pass after the velocity update, counting the joint torque twice and
  // the velocity-product terms at the new velocity (bullet3 #2966, #4451).
  kStock,
  // The feedback pass runs with joint velocities and torques zeroed, so it
  // only adds constraint forces: the feedback then describes the state at the
  // start of the step exactly.
  kCorrected,
};

class BulletSimulation {
 public:
  // Builds the btMultiBody (zero link damping, gyroscopic term on, no
  // coordinate-velocity clamp, no colliders).
  BulletSimulation(const RobotModel& model, JointFeedbackMode feedback = JointFeedbackMode::kCorrected);
  ~BulletSimulation();
  BulletSimulation(const BulletSimulation&) = delete;
  BulletSimulation& operator=(const BulletSimulation&) = delete;

  void SetState(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  void GetState(Eigen::VectorXd* q, Eigen::VectorXd* qd) const;

  // One semi-implicit Euler step of dt with the joint torques tau:
  // qd ← qd + dt·qdd(q, qd, tau), q ← q + dt·qd. Throws std::invalid_argument
  // if tau has the wrong size or dt is too small for Bullet to step.
  void Step(const Eigen::VectorXd& tau, double dt);

  // Bullet's forward dynamics at a state: sets (q, qd), takes one Step(tau,
  // dt) and writes the acceleration it integrated, qdd = (qd_after − qd)/dt
  // [rad/s²] (rounding ~ε·|qd|/dt). The state is then the step's end. With
  // `feedback`, joint_feedback() is the wrenches at (q, qd) under tau; without,
  // it is left as it was and the step skips the feedback pass (~30 % of its
  // time). A higher-order integrator evaluates its stages with it (Simulate).
  // Throws std::invalid_argument as SetState and Step.
  void Accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double dt,
                     Eigen::VectorXd* qdd, bool feedback = true);

  // M(q)⁻¹ (n × n) at the q of the last Accelerations: its step's
  // articulated-body factors applied to each unit joint torque (Bullet's
  // calcAccelerationDeltasMultiDof), O(n²) instead of a step per column.
  // Leaves the state at (q, the step's end velocity). Throws std::logic_error
  // before any Accelerations.
  void InverseMassMatrix(Eigen::MatrixXd* M_inverse);

  // Joint feedback of the last Step, describing the state at its start.
  const std::vector<HingeWrench>& joint_feedback() const { return feedback_; }

  // Pose of link i's frame B in the world as Bullet holds it (for tests).
  Eigen::Isometry3d LinkPose(int i) const;

 private:
  struct Impl;
  RobotModel model_;  // a copy: the simulation outlives temporaries
  std::unique_ptr<Impl> impl_;
  std::vector<HingeWrench> feedback_;

  void StepWith(const Eigen::VectorXd& tau, double dt, bool feedback);
};

}  // namespace idbench
