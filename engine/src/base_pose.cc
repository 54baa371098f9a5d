#include "idbench/engine/base_pose.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "idbench/engine/urdf.h"

namespace idbench {

Eigen::Isometry3d BasePose::X_WR() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = RotationFromRpy(Eigen::Vector3d(xyz_rpy[3], xyz_rpy[4], xyz_rpy[5]));
  X.translation() = Eigen::Vector3d(xyz_rpy[0], xyz_rpy[1], xyz_rpy[2]);
  return X;
}

bool BasePose::IsIdentity() const {
  for (double v : xyz_rpy) {
    if (v != 0.0) return false;
  }
  return true;
}

bool BasePose::IsValid(std::string* why) const {
  static const char* kNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (int i = 0; i < 6; ++i) {
    const double v = xyz_rpy[static_cast<size_t>(i)];
    const double bound = i < 3 ? 1e3 : 4.0 * std::numbers::pi;  // [m] a cell, [rad]
    if (!std::isfinite(v) || std::abs(v) > bound) {
      if (why) {
        std::ostringstream s;
        s << "base_pose." << kNames[i] << ": expected a finite value within ±" << bound << (i < 3 ? " m" : " rad")
          << ", got " << v;
        *why = s.str();
      }
      return false;
    }
  }
  return true;
}

bool ParseBasePose(const std::string& text, BasePose* pose, std::string* why) {
  std::array<double, 6> v{};
  size_t at = 0;
  for (int i = 0; i < 6; ++i) {
    const size_t comma = text.find(',', at);
    const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    const bool last = i == 5;
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(x) ||
        (last ? comma != std::string::npos : comma == std::string::npos)) {
      if (why) *why = "base_pose: expected six numbers x,y,z,roll,pitch,yaw [m, rad], got '" + text.substr(0, 200) + "'";
      return false;
    }
    v[static_cast<size_t>(i)] = x;
    at = comma + 1;
  }
  BasePose parsed{v};
  if (!parsed.IsValid(why)) return false;
  *pose = parsed;
  return true;
}

Eigen::Vector3d MountedGravity(const RobotModel& model, const BasePose& pose) {
  return pose.X_WR().linear().transpose() * Eigen::Vector3d(0.0, 0.0, -model.gravity_W().norm());
}

RobotModel MountRobot(const RobotModel& model, const BasePose& pose) {
  if (std::string why; !pose.IsValid(&why)) throw std::invalid_argument(why);
  return RobotModel(model.name(), model.links(), MountedGravity(model, pose), model.ground());
}

bool IsMountedAt(const RobotModel& model, const BasePose& pose) {
  const Eigen::Vector3d& g = model.gravity_W();
  return (g - MountedGravity(model, pose)).norm() <= 1e-9 * std::max(1.0, g.norm());
}

}  // namespace idbench
