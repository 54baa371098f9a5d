// The axis-aligned box, in a link's frame B, that holds the link's geometry:
// what bounds its centre of mass when nothing better is known (a rigid body's
// centre of mass lies in the convex hull of its material, and so in any box
// around it).
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "idbench/engine/robot_model.h"

namespace idbench {

// The smallest box in B around every visual and collision shape of the link:
// mesh vertices, box corners, and the boxes around cylinders and spheres in
// their own frames G (a cylinder's box holds the cylinder, so the result is
// conservative). std::nullopt when the link has no shapes (or only meshes
// without vertices).
std::optional<Eigen::AlignedBox3d> LinkBoundingBox_B(const Link& link);

// The link's own centre of mass (its inertia's p_BoBcm_B) against that box: a
// robot file whose shapes are not placed in the frames of its inertials
// (links drawn floating apart) has centres of mass far outside their boxes.
struct CenterOfMassGeometryCheck {
  Eigen::AlignedBox3d box_B;  // LinkBoundingBox_B
  double distance = 0.0;      // [m] from the centre of mass to the box; 0 inside
  // [m] the distance that counts as near: max(1 cm, 10 % of the box's
  // diagonal), for shapes that leave out some of the material.
  double tolerance = 0.0;
  bool contradicts() const { return distance > tolerance; }
};
// std::nullopt when the link has no shapes.
std::optional<CenterOfMassGeometryCheck> CheckCenterOfMassInGeometry(const Link& link);

}  // namespace idbench
