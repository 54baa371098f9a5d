// A robot under feedback control: a sampled controller (joint_controller.h)
// tracks a reference, holding its torque between samples, and the log holds
// what the robot records: the measured positions it acted on, the torque it
// commanded, and the reference.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "idbench/engine/joint_controller.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/sensor_model.h"
#include "idbench/engine/simulation.h"
#include "idbench/engine/trajectory.h"

namespace idbench {

// The plant's forward dynamics: qdd [rad/s²] at (q, qd) under the applied
// joint torques τ [N m], the drives' friction and rotor inertia included.
using PlantDynamics = std::function<void(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                         const Eigen::VectorXd& tau, Eigen::VectorXd* qdd)>;

struct ClosedLoopLog {
  // t; q as measured (noise, quantum: what the controller saw); qd, qdd the
  // plant's exact ones when sensors.record_derivatives; tau the commanded
  // (= applied) torque plus the torque sensing's noise.
  JointLog log;
  Eigen::MatrixXd q_ref;  // reference positions at the samples [rad] (n_samples × n_dof)
};

// Runs round(duration/dt) steps of dt from the reference's state at t = 0.
// At every sample (every sensors.StepsPerSample(dt) steps, from the first)
// q is measured (SensorSampler::MeasureQ), the controller commands τ from it
// and the reference, and τ is held to the next sample (zero-order hold); the
// state advances by the classical Runge–Kutta step under the held τ. Throws
// std::invalid_argument on mismatched sizes or options, std::runtime_error
// when the state becomes non-finite.
ClosedLoopLog RunClosedLoop(const Trajectory& reference, double duration, double dt, JointController* controller,
                            const SensorOptions& sensors, const PlantDynamics& plant);

// The closed loop around Bullet's forward dynamics (BulletSimulation::
// Accelerations) of `model`, with its joints' friction and rotor inertia
// (inverse_dynamics.h AddJointDynamicsTorque) acting against the applied
// torque; the controller's feed-forward, if any, uses `model` too. Uses
// options.dt and options.duration. Throws as RunClosedLoop and
// JointController.
ClosedLoopLog SimulateClosedLoop(const RobotModel& model, const Trajectory& reference,
                                 const SimulationOptions& options, const JointControllerOptions& controller,
                                 const SensorOptions& sensors);

}  // namespace idbench
