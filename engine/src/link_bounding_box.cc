#include "idbench/engine/link_bounding_box.h"

#include <algorithm>
#include <vector>

namespace idbench {
namespace {

// Grows box_B by a shape's points, expressed in its frame G.
void ExtendByShape(const Shape& shape, Eigen::AlignedBox3d* box_B) {
  if (shape.kind == Shape::Kind::kMesh) {
    if (!shape.mesh) return;
    for (const Eigen::Vector3d& p_GoV_G : shape.mesh->vertices) box_B->extend(shape.X_BG * p_GoV_G);
    return;
  }
  // Box: full edges; cylinder (r, r, length) and sphere (r, r, r): the box
  // around them, centred on G.
  const Eigen::Vector3d half = shape.kind == Shape::Kind::kBox        ? 0.5 * shape.size
                               : shape.kind == Shape::Kind::kCylinder ? Eigen::Vector3d(shape.size.x(), shape.size.y(), 0.5 * shape.size.z())
                                                                      : shape.size;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p_GoC_G((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                  (corner & 4 ? 1 : -1) * half.z());
    box_B->extend(shape.X_BG * p_GoC_G);
  }
}

}  // namespace

std::optional<Eigen::AlignedBox3d> LinkBoundingBox_B(const Link& link) {
  Eigen::AlignedBox3d box_B;  // empty
  for (const std::vector<Shape>* shapes : {&link.shapes, &link.collision_shapes})
    for (const Shape& shape : *shapes) ExtendByShape(shape, &box_B);
  if (box_B.isEmpty()) return std::nullopt;
  return box_B;
}

std::optional<CenterOfMassGeometryCheck> CheckCenterOfMassInGeometry(const Link& link) {
  const std::optional<Eigen::AlignedBox3d> box_B = LinkBoundingBox_B(link);
  if (!box_B) return std::nullopt;
  CenterOfMassGeometryCheck check;
  check.box_B = *box_B;
  check.distance = box_B->exteriorDistance(link.inertia.p_BoBcm_B);
  check.tolerance = std::max(0.01, 0.1 * box_B->diagonal().norm());
  return check;
}

}  // namespace idbench
