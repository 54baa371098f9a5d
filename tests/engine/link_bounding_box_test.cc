#include "idbench/engine/link_bounding_box.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace idbench {
namespace {

void ExpectBox(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  EXPECT_LT((box.min() - lo).norm(), 1e-12) << box.min().transpose();
  EXPECT_LT((box.max() - hi).norm(), 1e-12) << box.max().transpose();
}

// A 0.2 × 0.4 × 0.6 box turned 90° about z and moved to x = 1: its 0.4 edge
// now lies along x of B, its 0.2 edge along y (worked out by hand).
TEST(LinkBoundingBoxTest, TurnedBoxIsBoundedByItsCorners) {
  Link link;
  Shape box;
  box.kind = Shape::Kind::kBox;
  box.size = Eigen::Vector3d(0.2, 0.4, 0.6);
  box.X_BG = Eigen::Translation3d(1.0, 0.0, 0.0) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ());
  link.shapes.push_back(box);
  ExpectBox(*LinkBoundingBox_B(link), Eigen::Vector3d(0.8, -0.1, -0.3), Eigen::Vector3d(1.2, 0.1, 0.3));
}

// Visual and collision shapes together: a cylinder (r 0.1, length 1, along z)
// and a collision mesh whose vertices reach beyond it.
TEST(LinkBoundingBoxTest, CylinderAndCollisionMeshTogether) {
  Link link;
  Shape cylinder;
  cylinder.kind = Shape::Kind::kCylinder;
  cylinder.size = Eigen::Vector3d(0.1, 0.1, 1.0);
  link.shapes.push_back(cylinder);
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.3, -0.2, 0.7)};
  Shape collision;
  collision.kind = Shape::Kind::kMesh;
  collision.mesh = mesh;
  collision.X_BG = Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.1));
  link.collision_shapes.push_back(collision);
  ExpectBox(*LinkBoundingBox_B(link), Eigen::Vector3d(-0.1, -0.2, -0.5), Eigen::Vector3d(0.3, 0.1, 0.8));
}

TEST(LinkBoundingBoxTest, LinkWithoutShapesHasNone) {
  Link link;
  EXPECT_FALSE(LinkBoundingBox_B(link).has_value());
  Shape empty_mesh;
  empty_mesh.kind = Shape::Kind::kMesh;  // no triangles read
  link.shapes.push_back(empty_mesh);
  EXPECT_FALSE(LinkBoundingBox_B(link).has_value());
}

}  // namespace
}  // namespace idbench
