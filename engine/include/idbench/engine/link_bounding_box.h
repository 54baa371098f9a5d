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

}  // namespace idbench
