// The excitation design in a cell (DesignOptions::scene, base_pose): the
// designed motion keeps the clearance to a table and a wall, checked at every
// 1 ms by an independent sampler (analytic point-to-box distances of every
// mesh vertex of every link, not the design's GJK), on a ceiling-mounted arm,
// and a cell that leaves no motion is explained per obstacle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/kinematics.h"
#include "idbench/engine/urdf.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {

const char* const kUrLike = IDBENCH_SOURCE_DIR "/tests/data/ur10e_like/ur10e_like.urdf";

std::vector<JointLimits> UrLikeLimits(const RobotModel& model) {
  const double qdd[6] = {3, 3, 5, 5, 5, 5};
  std::vector<JointLimits> limits;
  for (int j = 0; j < 6; ++j) limits.push_back(model.link(j).limits), limits.back().qdd_max = qdd[j];
  return limits;
}

DesignOptions CellDesignOptions() {
  DesignOptions o;
  o.harmonics = 3;
  o.f0 = 0.2;
  o.samples = 60;
  o.starts = 2;
  o.max_evaluations = 150;
  o.clearance = 0.01;
  return o;
}

Obstacle Box(const std::string& name, const Eigen::Vector3d& size, const Eigen::Vector3d& centre_W) {
  Obstacle o;
  o.name = name;
  o.shape.kind = Shape::Kind::kBox;
  o.shape.size = size;
  o.X_WO.translation() = centre_W;
  return o;
}

// Distance from a point to an axis-aligned box obstacle (≥ 0 outside, negative inside).
double PointBoxDistance(const Eigen::Vector3d& p_W, const Obstacle& box) {
  const Eigen::Vector3d d = (box.X_WO.inverse() * p_W).cwiseAbs() - 0.5 * box.shape.size;
  return d.maxCoeff() > 0.0 ? d.cwiseMax(0.0).norm() : d.maxCoeff();
}

// The least distance from any vertex of any link mesh to each obstacle over
// the trajectory sampled every 1 ms. The boxes reach beyond the arm's reach,
// so the closest feature of either is a face, and the least vertex distance
// is the mesh hull's distance.
std::vector<double> SampledClearance(const RobotModel& model, const BasePose& base, const std::vector<Obstacle>& boxes,
                                     const Trajectory& motion) {
  const Eigen::Isometry3d X_WR = base.X_WR();
  std::vector<double> least(boxes.size(), std::numeric_limits<double>::infinity());
  KinematicsData<double> k(model);
  JointState x(model.n_dof());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
  const long steps = std::lround(std::floor(motion.duration() * 1000.0 + 1e-9));
  for (long s = 0; s <= steps; ++s) {
    motion.Evaluate(s * 1e-3, &x);
    ComputeKinematicsT<double>(model, x.q, zero, zero, &k);
    for (int i = 0; i < model.n_links(); ++i) {
      const size_t b = static_cast<size_t>(i);
      for (const Shape& shape : model.link(i).CollisionShapes()) {
        if (!shape.mesh) continue;  // the arm's shapes are all meshes
        for (const Eigen::Vector3d& v_G : shape.mesh->vertices) {
          const Eigen::Vector3d p_W = X_WR * (k.p_WBo_W[b] + k.R_WB[b] * (shape.X_BG * v_G));
          for (size_t o = 0; o < boxes.size(); ++o) least[o] = std::min(least[o], PointBoxDistance(p_W, boxes[o]));
        }
      }
    }
  }
  return least;
}

// The UR10e-like arm on a table 0.8 m high (its base at the table top's
// height), a wall 0.5 m in front of the base: the design is usable and keeps
// the clearance to both at every millisecond of what the robot runs.
TEST(DesignInCellTest, TableAndWallKeepTheirClearanceAtEveryMillisecond) {
  const BasePose base{{0, 0, 0.8, 0, 0, 0}};
  const RobotModel model = MountRobot(LoadUrdfFile(kUrLike).model, base);
  DesignOptions o = CellDesignOptions();
  o.base_pose = base;
  const Obstacle table = Box("table", {4.0, 4.0, 0.05}, {0, 0, 0.775});
  const Obstacle wall = Box("wall", {0.1, 4.0, 4.0}, {0.55, 0, 1.0});
  o.scene.obstacles = {table, wall};
  const DesignResult r =
      DesignExcitation(DesignRegressor::JointTorque(model, FrictionModel{}), UrLikeLimits(model), o);
  ASSERT_TRUE(r.usable()) << r.Rejection() << "\n" << r.check.Explain();
  const std::vector<double> least = SampledClearance(model, base, {table, wall}, r.RobotTrajectory());
  EXPECT_GE(least[0], o.clearance) << "table";
  EXPECT_GE(least[1], o.clearance) << "wall";
  // The wall is in reach: the motion comes within 0.3 m of it (it constrains the design).
  EXPECT_LT(least[1], 0.3);
  // The re-check names the closest part of the cell, at the distance the sampler saw
  // (the design's shapes are 1 mm inflated hulls: up to 2 mm closer).
  const ConstraintMargin* closest = r.check.ClosestObstacle();
  ASSERT_NE(closest, nullptr);
  const double sampled_min = std::min(least[0], least[1]);
  EXPECT_EQ(closest->obstacle, least[0] < least[1] ? "table" : "wall");
  EXPECT_LE(closest->value, sampled_min + 1e-6);
  EXPECT_GE(closest->value, sampled_min - 2.5e-3);
}

// Upside down under a ceiling 2.5 m up (gravity along the base's +z): the
// design is usable, with the torques of the mounted model.
TEST(DesignInCellTest, CeilingMountedDesignIsFeasible) {
  const BasePose ceiling{{0, 0, 2.5, std::numbers::pi, 0, 0}};
  const RobotModel model = MountRobot(LoadUrdfFile(kUrLike).model, ceiling);
  DesignOptions o = CellDesignOptions();
  o.base_pose = ceiling;
  o.scene.obstacles = {Box("ceiling", {4.0, 4.0, 0.1}, {0, 0, 2.55})};
  const DesignResult r =
      DesignExcitation(DesignRegressor::JointTorque(model, FrictionModel{}), UrLikeLimits(model), o);
  EXPECT_TRUE(r.usable()) << r.Rejection() << "\n" << r.check.Explain();
  EXPECT_TRUE(r.check.feasible());
  // Unmounted, the model's gravity does not match the base pose: refused, naming the field.
  try {
    DesignExcitation(DesignRegressor::JointTorque(LoadUrdfFile(kUrLike).model, FrictionModel{}), UrLikeLimits(model),
                     o);
    FAIL() << "an unmounted model was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("base_pose: the model's gravity", 0), 0u) << e.what();
  }
}

// A pillar through the upper arm's path at every pose: no motion at all,
// explained per obstacle before any search.
TEST(DesignInCellTest, ACellWithoutRoomIsExplainedPerObstacle) {
  const RobotModel model = LoadUrdfFile(kUrLike).model;
  DesignOptions o = CellDesignOptions();
  Obstacle pillar;
  pillar.name = "pillar";
  pillar.shape.kind = Shape::Kind::kCylinder;
  pillar.shape.size = Eigen::Vector3d(0.4, 0.4, 2.0);
  pillar.X_WO.translation() = Eigen::Vector3d(0, 0, 1.0);  // around the shoulder
  o.scene.obstacles = {pillar};
  const DesignResult result = DesignExcitation(DesignRegressor::JointTorque(model, FrictionModel{}), UrLikeLimits(model), o);
  ASSERT_EQ(result.status, DesignStatus::kNoRoom) << "a design inside a pillar";
  EXPECT_TRUE(result.infeasibility.before_search);
  const std::string& what = result.infeasibility.explanation;
  EXPECT_NE(what.find("–pillar clearance"), std::string::npos) << what;
  EXPECT_NE(what.find("the scene's obstacle 'pillar' (obstacles[0], a cylinder of radius 0.4 m, 2 m long at (0, 0, 1) m)"),
            std::string::npos) << what;
  EXPECT_NE(what.find("clearance: "), std::string::npos) << what;
  EXPECT_NE(what.find(" at the home pose is below its minimum"), std::string::npos) << what;
}

}  // namespace
}  // namespace idbench
