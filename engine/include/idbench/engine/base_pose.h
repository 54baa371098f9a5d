// Mounting: where the robot's base frame R sits in the world W, gravity
// along W's −z. Every algorithm computes in R (the frame the robot file
// calls the world: RobotModel's W), so a mounting only turns gravity, seen
// from the base, g_R = R_WRᵀ·(0, 0, −g), and places the cell (scene.h) in
// R. A ceiling-mounted arm is roll = π; a wall-mounted one pitch = ±π/2.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <string>

#include "idbench/engine/robot_model.h"

namespace idbench {

struct BasePose {
  // [x, y, z] [m] then [roll, pitch, yaw] [rad] of R in W, as URDF's
  // <origin xyz rpy> (fixed axes: roll about x, pitch about y, yaw about z).
  std::array<double, 6> xyz_rpy{};

  Eigen::Isometry3d X_WR() const;
  bool IsIdentity() const;
  // Finite values, angles within ±4π; *why names `base_pose` and the entry.
  bool IsValid(std::string* why) const;
};

// "x,y,z,roll,pitch,yaw" (six finite numbers). False with *why quoting the text otherwise.
bool ParseBasePose(const std::string& text, BasePose* pose, std::string* why);

// The world's gravity (0, 0, −|g|) seen from a base mounted at `pose`:
// R_WRᵀ·(0, 0, −|g_model|) — the magnitude kept from model.
Eigen::Vector3d MountedGravity(const RobotModel& model, const BasePose& pose);

// The model with its gravity turned to MountedGravity (everything else as is).
// Throws std::invalid_argument (BasePose::IsValid's message) for a bad pose.
RobotModel MountRobot(const RobotModel& model, const BasePose& pose);

// Whether model's gravity is what a base at `pose` sees (to 1e-9 relative):
// a model MountRobot made for that pose, or any model when pose is the identity
// and its gravity is along its −z.
bool IsMountedAt(const RobotModel& model, const BasePose& pose);

}  // namespace idbench
