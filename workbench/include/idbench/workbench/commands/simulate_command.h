// `idbench simulate`: a simulated experiment written as a joint log. Bullet
// tracks a motion with computed torques; the sensor model samples it.
#pragma once

#include <string>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/sensor_model.h"
#include "idbench/engine/simulation.h"

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

  SimulationOptions simulation() const;
  // Checks what does not need the robot; *why names the bad option.
  bool IsValid(std::string* why) const;
};

// Simulates and measures over the motion's duration, the model mounted at
// options.base_pose (MountRobot). Throws
// std::invalid_argument on a robot/motion/sensor mismatch or a bad trajectory
// file (naming it) and std::runtime_error if the simulation diverges.
JointLog SimulateJointLog(const RobotModel& model, const SimulateOptions& options);

}  // namespace idbench
