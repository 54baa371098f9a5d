#include "idbench/render/robot_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "idbench/engine/paper6r.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

// The paper 6R at one pose, at rest (ComputeKinematics done).
RobotData PosedAtRest(const RobotModel& model) {
  RobotData data(model);
  Eigen::VectorXd q(6);
  q << 0.3, -0.7, 0.4, 1.1, -0.5, 0.9;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(model, q, zero, zero, &data);
  return data;
}

TEST(RobotSceneTest, Paper6rCylindersSitOnTheLinksAndEveryHingeIsMarked) {
  const RobotModel model = MakePaper6r();
  const RobotData data = PosedAtRest(model);
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

// A robot whose links have no shapes (meshes not found) still shows: a rod
// from each link's joint to its child's joint, a ball at the last link's
// centre of mass, and the hinges.
TEST(RobotSceneTest, LinksWithoutShapesGetRodsBetweenTheirJoints) {
  const RobotModel paper = MakePaper6r();
  std::vector<Link> links = paper.links();
  for (Link& l : links) l.shapes.clear();
  const RobotModel bare("bare", std::move(links));
  RobotData data(bare);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(6, 0.2, 1.2), zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(bare, q, zero, zero, &data);
  const Scene scene = BuildRobotScene(bare, data);
  int rods = 0, balls = 0;
  for (int i = 0; i < bare.n_links(); ++i) {
    const Eigen::Vector3f color = LinkColor(i);
    for (const ScenePrimitive& p : scene.primitives) {
      if (p.color != color) continue;
      if (p.kind == Shape::Kind::kSphere) {
        ++balls;
        EXPECT_LT((p.X_WG.translation() - data.p_WBo_W[5] - data.R_WB[5] * bare.link(5).inertia.p_BoBcm_B).norm(),
                  1e-12);
        continue;
      }
      ASSERT_LT(i, 5);
      ++rods;
      const Eigen::Vector3d half = 0.5 * p.size.z() * p.X_WG.linear().col(2);
      EXPECT_LT((p.X_WG.translation() - half - data.p_WBo_W[static_cast<size_t>(i)]).norm(), 1e-12);
      EXPECT_LT((p.X_WG.translation() + half - data.p_WBo_W[static_cast<size_t>(i + 1)]).norm(), 1e-12);
    }
  }
  EXPECT_EQ(balls, 1);
  EXPECT_GE(rods, 4);  // joints that coincide get no rod
  EXPECT_FALSE(scene.BoundingPoints().empty());
}

// The ground links (issue 35: the table and pedestal the arm stands on) are
// drawn where the URDF puts them, carried by the base pose; the stand-in
// pedestal is not added under them. Truth: table_arm.urdf's shapes.
TEST(RobotSceneTest, GroundLinksAreDrawnWhereTheRobotFilePutsThem) {
  const RobotModel model = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf").model;
  RobotData data(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
  ComputeKinematics(model, zero, zero, zero, &data);
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(1.0, 2.0, 0.0);
  X_WR.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Scene scene = BuildRobotScene(model, data, X_WR);
  auto find = [&](Shape::Kind kind, const Eigen::Vector3d& size) -> const ScenePrimitive* {
    for (const ScenePrimitive& p : scene.primitives)
      if (p.kind == kind && (p.size - size).norm() < 1e-12) return &p;
    return nullptr;
  };
  const ScenePrimitive* table = find(Shape::Kind::kBox, Eigen::Vector3d(2, 2, 0.5));
  ASSERT_NE(table, nullptr);
  EXPECT_LT((table->X_WG.translation() - X_WR * Eigen::Vector3d(0, 0, 0.25)).norm(), 1e-12);
  const ScenePrimitive* pedestal = find(Shape::Kind::kCylinder, Eigen::Vector3d(0.06, 0.06, 0.1));
  ASSERT_NE(pedestal, nullptr);  // collision shape only: drawn from it
  EXPECT_LT((pedestal->X_WG.translation() - X_WR * Eigen::Vector3d(0, 0, 0.55)).norm(), 1e-12);
  const ScenePrimitive* lamp = find(Shape::Kind::kSphere, Eigen::Vector3d(0.1, 0.1, 0.1));
  ASSERT_NE(lamp, nullptr);
  EXPECT_LT((lamp->X_WG.translation() - X_WR * Eigen::Vector3d(5, 0, 2)).norm(), 1e-12);
  // Upright, no stand-in pedestal joins them (the first joint is 0.6 m up).
  const Scene upright = BuildRobotScene(model, data);
  int cylinders_from_floor = 0;
  for (const ScenePrimitive& p : upright.primitives)
    cylinders_from_floor += p.kind == Shape::Kind::kCylinder && std::abs(p.X_WG.translation().z() - 0.3) < 1e-12;
  EXPECT_EQ(cylinders_from_floor, 0);
}

// Mounted: every primitive of the upright scene carried by X_WR (no
// pedestal); the cell's obstacles at their own poses, in the obstacle colour.
TEST(RobotSceneTest, MountedRobotIsCarriedByTheBasePoseAndObstaclesStandWhereTheCellPutsThem) {
  const RobotModel model = MakePaper6r();
  const RobotData data = PosedAtRest(model);
  const Scene upright = BuildRobotScene(model, data);
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.linear() = Eigen::AngleAxisd(3.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_WR.translation() = Eigen::Vector3d(0.2, -0.1, 2.5);
  const Scene mounted = BuildRobotScene(model, data, X_WR);
  ASSERT_EQ(mounted.primitives.size(), upright.primitives.size());
  for (size_t i = 0; i < upright.primitives.size(); ++i) {
    EXPECT_TRUE(mounted.primitives[i].X_WG.isApprox(X_WR * upright.primitives[i].X_WG, 1e-12)) << i;
    EXPECT_EQ(mounted.primitives[i].size, upright.primitives[i].size) << i;
  }
  Cell cell;
  Obstacle box, ball;
  box.shape.kind = Shape::Kind::kBox;
  box.shape.size = Eigen::Vector3d(0.5, 1.0, 2.0);
  box.X_WO.translation() = Eigen::Vector3d(1, 2, 1);
  ball.shape.kind = Shape::Kind::kSphere;
  ball.shape.size = Eigen::Vector3d::Constant(0.3);
  ball.X_WO.translation() = Eigen::Vector3d(-1, 0, 0.5);
  cell.obstacles = {box, ball};
  Scene scene;
  AddCellObstacles(cell, &scene);
  ASSERT_EQ(scene.primitives.size(), 2u);
  EXPECT_EQ(scene.primitives[0].kind, Shape::Kind::kBox);
  EXPECT_EQ(scene.primitives[0].size, box.shape.size);
  EXPECT_TRUE(scene.primitives[0].X_WG.isApprox(box.X_WO));
  EXPECT_EQ(scene.primitives[1].kind, Shape::Kind::kSphere);
  EXPECT_EQ(scene.primitives[1].X_WG.translation(), ball.X_WO.translation());
  EXPECT_EQ(scene.primitives[0].color, kObstacleColor);
}

}  // namespace
}  // namespace idbench
