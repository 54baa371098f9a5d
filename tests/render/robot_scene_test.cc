#include "idbench/render/robot_scene.h"

#include <gtest/gtest.h>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

TEST(RobotSceneTest, Paper6rCylindersSitOnTheLinksAndEveryHingeIsMarked) {
  const RobotModel model = MakePaper6r();
  RobotData data(model);
  Eigen::VectorXd q(6);
  q << 0.3, -0.7, 0.4, 1.1, -0.5, 0.9;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(model, q, zero, zero, &data);
  const Scene scene = BuildRobotScene(model, data);
  // One cylinder per link, then its hinge marker.
  ASSERT_EQ(scene.primitives.size(), 12u);
  const Paper6rGeometry geometry;
  for (int i = 0; i < 6; ++i) {
    const ScenePrimitive& link = scene.primitives[static_cast<size_t>(2 * i)];
    const ScenePrimitive& hinge = scene.primitives[static_cast<size_t>(2 * i + 1)];
    // The cylinder: centred on the centroid, axis along the link's x (paper e1).
    EXPECT_LT((link.X_WG.translation() - data.p_WBcm_W[static_cast<size_t>(i)]).norm(), 1e-12) << i;
    EXPECT_NEAR(std::abs(link.X_WG.linear().col(2).dot(data.R_WB[static_cast<size_t>(i)].col(0))), 1.0, 1e-12) << i;
    EXPECT_EQ(link.size, Eigen::Vector3d(geometry.radius[static_cast<size_t>(i)], geometry.radius[static_cast<size_t>(i)],
                                         geometry.length[static_cast<size_t>(i)]));
    // The hinge: at the joint, along its axis, outside both links.
    EXPECT_LT((hinge.X_WG.translation() - data.p_WBo_W[static_cast<size_t>(i)]).norm(), 1e-12) << i;
    EXPECT_NEAR(hinge.X_WG.linear().col(2).dot(data.axis_W[static_cast<size_t>(i)]), 1.0, 1e-12) << i;
    const double r_max = std::max(geometry.radius[static_cast<size_t>(i)],
                                  i > 0 ? geometry.radius[static_cast<size_t>(i - 1)] : 0.0);
    const bool along_link = i == 0 || i == 3 || i == 5;  // O1, O4, O6 turn about the link's own axis
    if (along_link) {
      EXPECT_GT(hinge.size.x(), r_max) << i;
    } else {
      EXPECT_GT(hinge.size.z() / 2.0, r_max) << i;
    }
    EXPECT_NE(hinge.color, link.color);
  }
}

TEST(RobotSceneTest, BoundingPointsAreTheBoxCorners) {
  Scene scene;
  ScenePrimitive box;
  box.kind = Shape::Kind::kBox;
  box.size = Eigen::Vector3d(2, 4, 6);
  box.X_WG.translation() = Eigen::Vector3d(10, 0, 0);
  scene.primitives.push_back(box);
  const std::vector<Eigen::Vector3d> points = scene.BoundingPoints();
  ASSERT_EQ(points.size(), 8u);
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_EQ(lo, Eigen::Vector3d(9, -2, -3));
  EXPECT_EQ(hi, Eigen::Vector3d(11, 2, 3));
}

}  // namespace
}  // namespace idbench
