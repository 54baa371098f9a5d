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

// A vertical cylinder (its axis along z of W).
Obstacle Cylinder(const std::string& name, double radius, double length, const Eigen::Vector3d& centre_W) {
  Obstacle o;
  o.name = name;
  o.shape.kind = Shape::Kind::kCylinder;
  o.shape.size = Eigen::Vector3d(radius, radius, length);
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
  o.scene.obstacles = {Cylinder("pillar", 0.4, 2.0, {0, 0, 1.0})};  // around the shoulder
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

// An obstacle named "ground" is an obstacle, not the floor (issue 35): the
// pillar under that name leaves no room (exit 1), explained per obstacle,
// with no advice about the floor.
TEST(DesignInCellTest, AnObstacleNamedGroundIsNotTheFloor) {
  const RobotModel model = LoadUrdfFile(kUrLike).model;
  DesignOptions o = CellDesignOptions();
  o.scene.obstacles = {Cylinder("ground", 0.4, 2.0, {0, 0, 1.0})};
  o.scene.floor = false;
  const DesignResult result = DesignExcitation(DesignRegressor::JointTorque(model, FrictionModel{}), UrLikeLimits(model), o);
  ASSERT_EQ(result.status, DesignStatus::kNoRoom) << result.infeasibility.explanation;
  const std::string& what = result.infeasibility.explanation;
  EXPECT_NE(what.find("the scene's obstacle 'ground' (obstacles[0], a cylinder of radius 0.4 m"), std::string::npos) << what;
  EXPECT_EQ(what.find("floor"), std::string::npos) << what;
}

// ---- The robot file's fixed links and contact at q = 0 (issue 35) ----

// A point's exact distance to a vertical cylinder (axis along z through c,
// radius r, half length h; negative inside).
double PointCylinderDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& c, double r, double h) {
  const double radial = std::hypot(p.x() - c.x(), p.y() - c.y()) - r, axial = std::abs(p.z() - c.z()) - h;
  return std::max(radial, axial) > 0.0 ? std::hypot(std::max(radial, 0.0), std::max(axial, 0.0))
                                       : std::max(radial, axial);
}

// Points along the 12 edges of a box (edges `size`, axes R, centre c), every `step` metres.
std::vector<Eigen::Vector3d> BoxEdgePoints(const Eigen::Matrix3d& R, const Eigen::Vector3d& c,
                                           const Eigen::Vector3d& size, double step) {
  std::vector<Eigen::Vector3d> points;
  for (int axis = 0; axis < 3; ++axis) {
    const int n = static_cast<int>(std::ceil(size[axis] / step));
    for (int corner = 0; corner < 4; ++corner) {
      Eigen::Vector3d p_G;
      p_G[(axis + 1) % 3] = (corner & 1 ? 0.5 : -0.5) * size[(axis + 1) % 3];
      p_G[(axis + 2) % 3] = (corner & 2 ? 0.5 : -0.5) * size[(axis + 2) % 3];
      for (int k = 0; k <= n; ++k) {
        p_G[axis] = (static_cast<double>(k) / n - 0.5) * size[axis];
        points.push_back(c + R * p_G);
      }
    }
  }
  return points;
}

Eigen::Matrix3d Rot(const Eigen::Vector3d& axis, double angle) { return Eigen::AngleAxisd(angle, axis).toRotationMatrix(); }

// tests/data/table_arm, sampled every 1 ms with its own kinematics (written
// from the file: l1 about z at 0.6 m, l2 about y 0.15 m above, l3 about y
// 0.4 m further): the least distance of l2's and l3's box edges (every 5 mm)
// to the table (2 × 2 × 0.5 m, top at 0.5 m) and to the pedestal (r 0.06 m,
// 0.5..0.6 m).
double TableArmClearance(const Trajectory& motion) {
  const Eigen::Vector3d table_centre(0, 0, 0.25), table_size(2.0, 2.0, 0.5);
  Obstacle table = Box("table", table_size, table_centre);
  double least = std::numeric_limits<double>::infinity();
  JointState x(3);
  const long steps = std::lround(std::floor(motion.duration() * 1000.0 + 1e-9));
  for (long s = 0; s <= steps; ++s) {
    motion.Evaluate(s * 1e-3, &x);
    const Eigen::Matrix3d R_W2 = Rot(Eigen::Vector3d::UnitZ(), x.q[0]) * Rot(Eigen::Vector3d::UnitY(), x.q[1]);
    const Eigen::Matrix3d R_W3 = R_W2 * Rot(Eigen::Vector3d::UnitY(), x.q[2]);
    const Eigen::Vector3d o2(0, 0, 0.75), o3 = o2 + R_W2 * Eigen::Vector3d(0, 0, 0.4);
    std::vector<Eigen::Vector3d> points = BoxEdgePoints(R_W2, o2 + R_W2 * Eigen::Vector3d(0, 0, 0.2), {0.06, 0.06, 0.4}, 5e-3);
    const std::vector<Eigen::Vector3d> l3 = BoxEdgePoints(R_W3, o3 + R_W3 * Eigen::Vector3d(0, 0, 0.15), {0.05, 0.05, 0.3}, 5e-3);
    points.insert(points.end(), l3.begin(), l3.end());
    for (const Eigen::Vector3d& p : points) {
      least = std::min({least, PointBoxDistance(p, table), PointCylinderDistance(p, {0, 0, 0.55}, 0.06, 0.05)});
    }
  }
  return least;
}

// The arm on its table (the table and the pedestal are its file's fixed
// links, no obstacle in the scene): the design keeps every link above the
// table, checked every 1 ms by the sampler above. The same design with the
// fixed links dropped (as before issue 35, when only the floor was checked)
// drives the arm into the table.
TEST(DesignInCellTest, TheRobotFilesTableKeepsItsClearanceAtEveryMillisecond) {
  const RobotModel model = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf").model;
  ASSERT_EQ(model.ground().size(), 3u);
  std::vector<JointLimits> limits;
  for (const Link& link : model.links()) limits.push_back(link.limits), limits.back().qdd_max = 5.0;
  DesignOptions o = CellDesignOptions();
  o.starts = 1;
  o.max_evaluations = 100;
  const DesignResult r = DesignExcitation(DesignRegressor::JointTorque(model, FrictionModel{}), limits, o);
  ASSERT_TRUE(r.usable()) << r.Rejection() << "\n" << r.check.Explain();
  const double least = TableArmClearance(r.RobotTrajectory());
  EXPECT_GE(least, o.clearance - 1e-6);
  const RobotModel floor_only(model.name(), model.links(), model.gravity_W());
  const DesignResult old = DesignExcitation(DesignRegressor::JointTorque(floor_only, FrictionModel{}), limits, o);
  ASSERT_TRUE(old.usable()) << old.Rejection();
  EXPECT_LT(TableArmClearance(old.RobotTrajectory()), -0.02);  // inside the table
  std::printf("table arm: least %.4g m (fixed links ignored: %.4g m)\n", least, TableArmClearance(old.RobotTrajectory()));
}

// A SCARA-like arm (two vertical joints) whose first link touches a post at
// q = 0: the design may not sweep it into the post — checked every 1 ms by
// points every 2.5 mm along the link's long edges against the post's exact
// cylinder (vertical: every height has the same section) — where, with that
// pair dropped as before issue 35, it sweeps centimetres in.
TEST(DesignInCellTest, ALinkTouchingAPostAtHomeNeverSweepsIntoIt) {
  std::vector<Link> links(2);
  const Eigen::Vector3d size[2] = {{0.5, 0.1, 0.1}, {0.3, 0.08, 0.08}};
  for (int i = 0; i < 2; ++i) {
    Link& l = links[static_cast<size_t>(i)];
    l.name = i == 0 ? "arm" : "forearm";
    l.joint_name = i == 0 ? "j1" : "j2";
    l.parent = i - 1;
    l.X_PJ.translation() = Eigen::Vector3d(i == 0 ? 0.0 : 0.5, 0, 0);
    l.inertia.mass = 2.0 - i;
    l.inertia.p_BoBcm_B = Eigen::Vector3d(0.5 * size[i].x(), 0.02, 0.15);
    l.inertia.I_Bcm_B = Eigen::Vector3d(0.002, 0.02 + 0.01 * i, 0.03).asDiagonal();
    l.limits.q_min = -2.5, l.limits.q_max = 2.5, l.limits.qd_max = 2.0, l.limits.qdd_max = 5.0, l.limits.tau_max = 50.0;
    Shape box;
    box.kind = Shape::Kind::kBox;
    box.size = size[i];
    box.X_BG.translation() = Eigen::Vector3d(0.5 * size[i].x(), 0, 0.15);
    l.shapes.push_back(box);
  }
  const RobotModel model("scara", links);
  std::vector<JointLimits> limits = {links[0].limits, links[1].limits};
  DesignOptions o = CellDesignOptions();
  o.starts = 1;
  o.max_evaluations = 100;
  const Obstacle post = Cylinder("post", 0.05, 1.0, {0.3, 0.1, 0.5});  // touching the arm's side y = 0.05 at q = 0
  o.scene.obstacles = {post};
  // The least signed distance of the arm's long edges to the post, every 1 ms.
  auto sampled = [&](const Trajectory& motion) {
    double least = std::numeric_limits<double>::infinity();
    JointState x(2);
    const long steps = std::lround(std::floor(motion.duration() * 1000.0 + 1e-9));
    for (long s = 0; s <= steps; ++s) {
      motion.Evaluate(s * 1e-3, &x);
      const Eigen::Matrix3d R = Rot(Eigen::Vector3d::UnitZ(), x.q[0]);
      for (const Eigen::Vector3d& p : BoxEdgePoints(R, R * Eigen::Vector3d(0.25, 0, 0.15), size[0], 2.5e-3)) {
        least = std::min(least, PointCylinderDistance(p, post.X_WO.translation(), 0.05, 0.5));
      }
    }
    return least;
  };
  const DesignRegressor regressor = DesignRegressor::JointTorque(model, FrictionModel{});
  const DesignResult r = DesignExcitation(regressor, limits, o);
  ASSERT_TRUE(r.usable()) << r.Rejection() << "\n" << r.check.Explain();
  const double least = sampled(r.RobotTrajectory());
  EXPECT_GE(least, -ClearanceModel::kContactTolerance - 1e-6);
  // With the pair dropped (no post to keep from), the motion sweeps the arm into it.
  o.scene.obstacles.clear();
  const double dropped = sampled(DesignExcitation(regressor, limits, o).RobotTrajectory());
  EXPECT_LT(dropped, -0.02);
  std::printf("scara: least %.4g m (pair dropped: %.4g m)\n", least, dropped);
}

}  // namespace
}  // namespace idbench
