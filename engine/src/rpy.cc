// URDF roll-pitch-yaw angles (declared in urdf.h).
#include <Eigen/Geometry>
#include <cmath>

#include "idbench/engine/urdf.h"

namespace idbench {

Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  // R = Rz(y)·Ry(p)·Rx(r) has first column (cy·cp, sy·cp, −sp). Take yaw from
  // it (arbitrary, here 0, when cp = 0), then read pitch and roll from
  // M = Rz(y)ᵀ·R = Ry(p)·Rx(r) = [cp  sp·sr  sp·cr; 0  cr  −sr; −sp  cp·sr  cp·cr].
  // Near gimbal lock the yaw is poorly determined, but M's entries used here
  // have magnitude ~1 or are exact given that yaw, so Rz(y)·Ry(p)·Rx(r)
  // reproduces R to rounding for every pitch.
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d M = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
  const double pitch = std::atan2(-M(2, 0), M(0, 0));
  const double roll = std::atan2(-M(1, 2), M(1, 1));
  return Eigen::Vector3d(roll, pitch, yaw);
}

}  // namespace idbench
