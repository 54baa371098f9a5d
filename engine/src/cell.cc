#include "idbench/engine/cell.h"

#include <cmath>
#include <string>

namespace idbench {

bool Cell::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (static_cast<int>(obstacles.size()) > kMaxObstacles) {
    return fail("obstacles: at most " + std::to_string(kMaxObstacles) + " obstacles, got " +
                std::to_string(obstacles.size()));
  }
  constexpr double kMaxSize = 100.0;  // [m]
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const Obstacle& o = obstacles[i];
    const std::string where = "obstacles[" + std::to_string(i) + "]";
    const Eigen::Vector3d& s = o.shape.size;
    if (!s.allFinite() || !(s.minCoeff() > 0.0) || s.maxCoeff() > kMaxSize) {
      return fail(where + ".size: expected finite sizes in (0, 100] m");
    }
    if (o.shape.kind == Shape::Kind::kMesh && (o.shape.mesh == nullptr || o.shape.mesh->vertices.empty())) {
      return fail(where + ".path: the mesh has no vertices");
    }
    const Eigen::Matrix3d& R = o.X_WO.linear();
    if (!o.X_WO.matrix().allFinite() || !(R.transpose() * R).isIdentity(1e-9) || !(R.determinant() > 0.0)) {
      return fail(where + ".pose: expected a finite rigid pose");
    }
  }
  return true;
}

std::string Cell::ObstacleName(int i) const {
  const std::string& name = obstacles.at(static_cast<size_t>(i)).name;
  return name.empty() ? "obstacle " + std::to_string(i) : name;
}

}  // namespace idbench
