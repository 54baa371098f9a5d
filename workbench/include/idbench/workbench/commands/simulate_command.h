// `idbench simulate`: a simulated experiment written as a joint log. Bullet
// tracks a motion with computed torques; the sensor model samples it. Given a
// transmission (transmission.h), the log is written on the motor side, as a
// geared robot's controller records it, with each motor's own friction and
// rotor inertia.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/closed_loop.h"
#include "idbench/engine/sensor_model.h"
#include "idbench/engine/simulation.h"
#include "idbench/engine/transmission.h"

namespace idbench {

struct SimulateOptions {
  std::string robot = "puma560";        // built-in name or URDF path
  std::string trajectory = "general";   // built-in motion or .json/.csv file (trajectory_file.h)
  double paper_accel_deg_s2 = 30.0;     // acceleration of the "paper" motion [deg/s²]
  double duration = 10.0;               // [s] of a built-in motion; a file brings its own
  double dt = 1e-3;                     // simulation step [s]
  SensorOptions sensors;
  BasePose base_pose;                   // the robot's base in the world: gravity along the world's −z
  std::string out = "out/log.csv";
  // A motor-side log when not empty: "urdf" takes the robot URDF's
  // <transmission> elements; else a JSON or YAML file holding a transmission
  // as a log description's "transmission" ({"reduction": [N1, ...]} or
  // {"actuator_from_joint": [[...], ...], "joint_offset": [...]}).
  std::string transmission;
  // The motors' own terms (truth), acting on θm and entering the joint
  // torques through Aᵀ: one value for every motor or one per motor; empty:
  // none. Only with a transmission.
  std::vector<double> motor_viscous;        // Fv_k [N m s/rad of the motor]
  std::vector<double> motor_coulomb;        // Fc_k [N m]
  std::vector<double> motor_rotor_inertia;  // Ia_k [kg m²]
  // A closed loop when not empty: a controller file (controller_file.h) whose
  // PID, sampled at sensors.rate_hz, tracks the trajectory from the measured
  // positions; the log adds the reference (qr1..qrn). Joint side only.
  std::string controller;

  SimulationOptions simulation() const;
  // The files simulate writes: out and, with a transmission, its log
  // description beside it (out with the extension .json).
  std::vector<std::string> Outputs() const;
  // Checks what does not need the robot, and that no output is one of the
  // inputs (robot, trajectory or transmission file, however spelled: it would
  // be overwritten); *why names the bad option.
  bool IsValid(std::string* why) const;
};

// Simulates and measures over the motion's duration, the model mounted at
// options.base_pose (MountRobot). Throws
// std::invalid_argument on a robot/motion/sensor mismatch or a bad trajectory
// file (naming it) and std::runtime_error if the simulation diverges.
JointLog SimulateJointLog(const RobotModel& model, const SimulateOptions& options);

// The closed loop (options.controller set): Bullet under the controller of
// that file, the model mounted at options.base_pose, measured by
// options.sensors (closed_loop.h). Throws std::invalid_argument naming the
// controller file and its key, or as SimulateJointLog.
ClosedLoopLog SimulateClosedLoopLog(const RobotModel& model, const SimulateOptions& options);

// A closed loop that did not hold its reference: the largest measured
// tracking error |q − q_ref| above kLostTrackingRad (5.7°, far beyond what a
// tuned arm's controller leaves), named by the joint's URDF name and the
// time; nullopt when it held. The log is still of the motion that happened.
inline constexpr double kLostTrackingRad = 0.1;
std::optional<std::string> LostTrackingWarning(const RobotModel& model, const ClosedLoopLog& closed);

// A motor-side log and the same experiment on the joint side.
struct MotorSideLog {
  // Rows are samples, columns motors, in a joint log's fields: q = θm = A·(q − q0) [rad], qd = θ̇m = A·q̇
  // [rad/s] and qdd the joint accelerations [rad/s²] (a log has no motor-side ones; both empty when not
  // recorded), tau = τm = A⁻ᵀ·τ [N m].
  JointLog motor;
  Transmission transmission;
  JointLog joint;            // the same experiment on the joint side, noise-free (τ = Aᵀ·τm)
};

// The transmission options.transmission names: nullopt when empty; "urdf":
// `from_urdf` (the robot file's), or std::invalid_argument when it has none;
// else the file's. Throws std::invalid_argument naming the field, or the
// file and its key, and checks it against n_dof.
std::optional<Transmission> SimulateTransmission(const SimulateOptions& options, int n_dof,
                                                 const std::optional<Transmission>& from_urdf);

// Simulates as SimulateJointLog, adds each motor's terms (options.motor_*)
// through Aᵀ to the joint torques, and measures on the motor side: the
// sensors' q_noise and q_resolution apply to θm, tau_noise to τm. Throws
// std::invalid_argument naming a motor_* field of the wrong size or sign.
MotorSideLog SimulateMotorSideLog(const RobotModel& model, const Transmission& transmission,
                                  const SimulateOptions& options);

// The log as CSV: t, qm*, qdm* and qdd* when recorded, taum*.
std::string FormatMotorSideLogCsv(const MotorSideLog& log);
// Its log description (joint_log_description.h), naming `csv_path`
// (relative to the description's folder) and the transmission, so that
// identify reads it through the same A and q0.
std::string FormatMotorSideLogDescription(const MotorSideLog& log, const std::string& csv_path);

}  // namespace idbench
