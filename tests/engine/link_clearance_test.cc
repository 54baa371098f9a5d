#include "idbench/engine/link_clearance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include "engine/test_meshes.h"
#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

using testing::RandomVector;

// Three links, one sphere each: distances are |c_a − c_b| − r_a − r_b and
// c_z − r to the ground.
RobotModel MakeSphereRobot(double r) {
  std::vector<Link> links(3);
  const Eigen::Vector3d joint_p[3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  const Eigen::Vector3d axis[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY()};
  const Eigen::Vector3d centre[3] = {{0, 0, 0.5}, {0.5, 0, 0}, {0.5, 0, 0}};
  for (int i = 0; i < 3; ++i) {
    Link& l = links[static_cast<size_t>(i)];
    l.name = "L" + std::to_string(i);
    l.parent = i - 1;
    l.X_PJ.translation() = joint_p[i];
    l.axis_J = axis[i];
    l.inertia.mass = 1.0;
    l.inertia.I_Bcm_B = 0.01 * Eigen::Matrix3d::Identity();
    Shape s;
    s.kind = Shape::Kind::kSphere;
    s.size.setConstant(r);
    s.X_BG.translation() = centre[i];
    l.shapes.push_back(s);
  }
  return RobotModel("spheres", std::move(links));
}

// Pose of a link's first shape at the kinematics in k: R_WG and p_WGo_W.
Eigen::Matrix3d ShapeRotation_W(const RobotModel& model, const KinematicsData<double>& k, int link) {
  return k.R_WB[static_cast<size_t>(link)] * model.link(link).shapes[0].X_BG.linear();
}
Eigen::Vector3d ShapeCentre_W(const RobotModel& model, const KinematicsData<double>& k, int link) {
  const size_t b = static_cast<size_t>(link);
  return k.p_WBo_W[b] + k.R_WB[b] * model.link(link).shapes[0].X_BG.translation();
}

TEST(LinkClearanceTest, SpheresMatchTheAnalyticDistances) {
  const double r = 0.1;
  const RobotModel model = MakeSphereRobot(r);
  const ClearanceModel clearance(model, 0.01);
  // Pairs: L0–ground, L1–ground, L2–ground, L2–L0 (L1–L0 and L2–L1 are joined).
  ASSERT_EQ(clearance.pairs().size(), 4u);
  KinematicsData<double> k(model);
  std::vector<Clearance> out;
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = RandomVector(3, 1.2, &rng), zero = Eigen::VectorXd::Zero(3);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    clearance.Compute(k, &out);
    for (size_t i = 0; i < out.size(); ++i) {
      const ClearancePair& p = clearance.pairs()[i];
      const auto centre = [&](int link) { return ShapeCentre_W(model, k, link); };
      const double expected = p.link_b < 0 ? centre(p.link_a).z() - r : (centre(p.link_a) - centre(p.link_b)).norm() - 2 * r;
      EXPECT_NEAR(out[i].distance, expected, 1e-6) << p.Name(model) << " trial " << trial;
    }
  }
}

// ∂d/∂q against central differences of the GJK distance, puma560's cylinders at random poses.
TEST(LinkClearanceTest, GradientMatchesFiniteDifferences) {
  const RobotModel model = MakePuma560();
  const ClearanceModel clearance(model, 0.005);
  ASSERT_FALSE(clearance.pairs().empty());
  KinematicsData<double> k(model);
  std::vector<Clearance> out, plus, minus;
  std::mt19937 rng(3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  int checked = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(6, 1.5, &rng);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    clearance.Compute(k, &out);
    for (size_t i = 0; i < out.size(); ++i) {
      if (out[i].distance < 0.02) continue;  // away from contact, where d is smooth
      const Eigen::VectorXd g = clearance.DistanceGradient(model, k, clearance.pairs()[i], out[i]);
      Eigen::VectorXd fd(6);
      for (int j = 0; j < 6; ++j) {
        const double h = 1e-4;  // GJK stops at a small tolerance: larger steps than usual
        Eigen::VectorXd qp = q, qm = q;
        qp[j] += h;
        qm[j] -= h;
        ComputeKinematicsT<double>(model, qp, zero, zero, &k);
        clearance.Compute(k, &plus);
        ComputeKinematicsT<double>(model, qm, zero, zero, &k);
        clearance.Compute(k, &minus);
        fd[j] = (plus[i].distance - minus[i].distance) / (2 * h);
      }
      ComputeKinematicsT<double>(model, q, zero, zero, &k);
      // GJK's witness points (hence n) are accurate to ~1e-3 rad, the distance far better.
      EXPECT_LT((g - fd).norm(), 2e-3 * std::max(1.0, fd.norm())) << clearance.pairs()[i].Name(model);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// Tracking each pair's minimum over many poses with the bounding-sphere
// pruning gives exactly the minimum of the full computation.
TEST(LinkClearanceTest, PrunedMinimumEqualsTheFullMinimum) {
  const RobotModel model = MakePuma560();
  const ClearanceModel clearance(model, 0.01);
  const size_t n_pairs = clearance.pairs().size();
  std::vector<double> full(n_pairs, std::numeric_limits<double>::infinity()), pruned = full;
  KinematicsData<double> k(model);
  std::vector<Clearance> out;
  std::mt19937 rng(4);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  for (int pose = 0; pose < 200; ++pose) {
    ComputeKinematicsT<double>(model, RandomVector(6, 2.5, &rng), zero, zero, &k);
    clearance.Compute(k, &out);
    for (size_t i = 0; i < n_pairs; ++i) full[i] = std::min(full[i], out[i].distance);
    clearance.Compute(k, &out, &pruned);
    for (size_t i = 0; i < n_pairs; ++i) pruned[i] = std::min(pruned[i], out[i].distance);
  }
  for (size_t i = 0; i < n_pairs; ++i) EXPECT_EQ(pruned[i], full[i]) << clearance.pairs()[i].Name(model);
}

// A pair already closer than the clearance at q = 0 is kept, held at its
// distance there (less 1 µm), never dropped; only joined pairs are left out.
// Sphere robot at q = 0: L0 0.4 m above the ground, L1 and L2 0.9 m, L2–L0
// |(1.5, 0, 0.5)| − 0.2 m apart. (6ab1a0b dropped the three ground pairs at
// a clearance of 1 m: asking for more gave less protection.)
TEST(LinkClearanceTest, PairsInsideTheClearanceAtHomeAreHeldThereNotDropped) {
  const double r = 0.1;
  const RobotModel model = MakeSphereRobot(r);
  const ClearanceModel clearance(model, 1.0);
  ASSERT_EQ(clearance.pairs().size(), 4u);
  const double tol = ClearanceModel::kHomeTolerance;
  for (const ClearancePair& p : clearance.pairs()) {
    const double home = p.link_b >= 0 ? std::hypot(1.5, 0.5) - 2 * r : (p.link_a == 0 ? 0.5 : 1.0) - r;
    EXPECT_NEAR(p.home_distance, home, 1e-6) << p.Name(model);
    EXPECT_NEAR(p.minimum, std::min(1.0, home - tol), 1e-6) << p.Name(model);
  }
  EXPECT_EQ(clearance.n_held_at_home(), 3);
  ASSERT_EQ(clearance.excluded().size(), 2u);
  EXPECT_EQ(clearance.excluded()[0], "L1–L0: joined by joint ''");
}

// In contact by construction: spheres overlapping at q = 0 are left out; a
// base on the floor (its only joint vertical) too; but a link on the floor
// that a joint can raise is kept at its distance at q = 0.
TEST(LinkClearanceTest, OnlyContactByConstructionIsLeftOut) {
  std::vector<Link> links = MakeSphereRobot(0.1).links();
  links[0].shapes[0].X_BG.translation() = Eigen::Vector3d(0, 0, 0.05);  // L0 sinks 5 cm into the floor
  links[2].shapes[0].X_BG.translation() = Eigen::Vector3d(-1.0, 0, -0.8);  // L2 at (0, 0, 0.2): into L0
  const RobotModel model("contacts", links);
  const ClearanceModel clearance(model, 0.05);
  std::vector<std::string> names;
  for (const ClearancePair& p : clearance.pairs()) names.push_back(p.Name(model));
  EXPECT_EQ(names, (std::vector<std::string>{"L1–ground", "L2–ground"}));
  ASSERT_EQ(clearance.excluded().size(), 4u);  // L1–L0, L2–L1 joined; L0–ground base; L2–L0 overlap
  EXPECT_NE(clearance.excluded()[0].find("L0–ground: on the ground at q = 0"), std::string::npos);
  EXPECT_NE(clearance.excluded()[2].find("L2–L0: in contact at q = 0 (-0.05 m)"), std::string::npos);
  EXPECT_NEAR(clearance.pairs()[1].home_distance, 0.1, 1e-9);  // L2 0.2 m up, radius 0.1
  EXPECT_EQ(clearance.pairs()[1].minimum, 0.05);
  // Tilt L0's joint off the vertical: the base can dip, so it is kept, held at −0.05 m.
  links[0].axis_J = Eigen::Vector3d(1, 0, 0);
  const RobotModel tilting("tilting", links);
  const ClearanceModel kept(tilting, 0.05);
  ASSERT_EQ(kept.pairs()[0].Name(tilting), "L0–ground");
  EXPECT_NEAR(kept.pairs()[0].minimum, -0.05 - ClearanceModel::kHomeTolerance, 1e-9);
}

// The sphere robot's links as boxes, primitive or mesh (the same box as 12
// triangles).
RobotModel MakeBoxRobot(bool as_mesh) {
  const RobotModel spheres = MakeSphereRobot(0.1);
  std::vector<Link> links = spheres.links();
  const Eigen::Vector3d edges(0.3, 0.12, 0.2);
  const auto mesh = std::make_shared<const TriangleMesh>(testing::BoxMesh(edges));
  for (Link& l : links) {
    Shape& s = l.shapes[0];
    s.X_BG.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
    s.kind = as_mesh ? Shape::Kind::kMesh : Shape::Kind::kBox;
    s.size = as_mesh ? Eigen::Vector3d::Ones() : edges;
    if (as_mesh) s.mesh = mesh;
  }
  return RobotModel("boxes", std::move(links));
}

// Every shape is checked as its Minkowski sum with a 1 mm ball (Bullet's
// margin, outside the surface): a box mesh (through its convex hull) and the
// box primitive give the same distances, and those are the exact ones less
// 1 mm per shape: at most 2 mm short, conservative, corners included.
TEST(LinkClearanceTest, BoxMeshesAndBoxesGiveTheSameConservativeDistances) {
  const RobotModel boxes = MakeBoxRobot(false), meshes = MakeBoxRobot(true);
  const ClearanceModel box_clearance(boxes, 0.0), mesh_clearance(meshes, 0.0);
  ASSERT_EQ(box_clearance.pairs().size(), mesh_clearance.pairs().size());
  KinematicsData<double> k(boxes);
  std::vector<Clearance> d_box, d_mesh;
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = RandomVector(3, 1.2, &rng), zero = Eigen::VectorXd::Zero(3);
    ComputeKinematicsT<double>(boxes, q, zero, zero, &k);
    box_clearance.Compute(k, &d_box);
    mesh_clearance.Compute(k, &d_mesh);
    for (size_t i = 0; i < d_box.size(); ++i) {
      const ClearancePair& p = box_clearance.pairs()[i];
      EXPECT_NEAR(d_mesh[i].distance, d_box[i].distance, 1e-9) << p.Name(boxes) << " trial " << trial;
      if (p.link_b < 0) {  // exact: the lowest corner of the box
        const Eigen::Matrix3d R_WG = ShapeRotation_W(boxes, k, p.link_a);
        const Eigen::Vector3d c_W = ShapeCentre_W(boxes, k, p.link_a);
        const double lowest = c_W.z() - 0.5 * (R_WG.row(2).cwiseAbs() * Eigen::Vector3d(0.3, 0.12, 0.2))(0);
        EXPECT_NEAR(d_box[i].distance, lowest - 1e-3, 1e-9) << p.Name(boxes) << " trial " << trial;
      }
    }
  }
}

// Clearance checks a link's collision shapes when it has any, its drawn
// shapes otherwise.
TEST(LinkClearanceTest, CollisionShapesReplaceTheDrawnOnes) {
  const RobotModel spheres = MakeSphereRobot(0.1);
  std::vector<Link> links = spheres.links();
  for (Link& l : links) {
    l.collision_shapes = l.shapes;
    l.collision_shapes[0].size.setConstant(0.05);  // drawn 0.1, checked 0.05
  }
  const RobotModel model("collisions", std::move(links));
  const ClearanceModel drawn(spheres, 0.0), checked(model, 0.0);
  KinematicsData<double> k(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(3, 0.4), zero = Eigen::VectorXd::Zero(3);
  ComputeKinematicsT<double>(model, q, zero, zero, &k);
  std::vector<Clearance> d_drawn, d_checked;
  drawn.Compute(k, &d_drawn);
  checked.Compute(k, &d_checked);
  ASSERT_EQ(d_drawn.size(), d_checked.size());
  for (size_t i = 0; i < d_drawn.size(); ++i) {
    const double gained = checked.pairs()[i].link_b < 0 ? 0.05 : 0.1;  // the smaller radius, once or twice
    EXPECT_NEAR(d_checked[i].distance, d_drawn[i].distance + gained, 1e-9) << checked.pairs()[i].Name(model);
  }
}

// A mesh with many hull points (a 642-vertex sphere) is checked through a
// reduced inner hull grown by how far the full hull reaches beyond it: still
// conservative, and not much more. Bounds from the mesh itself: its lowest
// vertex (ground), and its inscribed and circumscribed spheres (r_in, r).
TEST(LinkClearanceTest, LargeMeshHullsAreReducedAndStayConservative) {
  constexpr double r = 0.1;
  const TriangleMesh sphere_mesh = testing::IcosphereMesh(r, 3);
  ASSERT_EQ(sphere_mesh.vertices.size(), 642u);
  double r_in = r;  // distance from the centre to the nearest face plane
  for (const Eigen::Vector3i& t : sphere_mesh.triangles) {
    const Eigen::Vector3d &a = sphere_mesh.vertices[t[0]], &b = sphere_mesh.vertices[t[1]],
                          &c = sphere_mesh.vertices[t[2]];
    r_in = std::min(r_in, std::abs(a.dot((b - a).cross(c - a).normalized())));
  }
  const RobotModel spheres = MakeSphereRobot(r);
  std::vector<Link> links = spheres.links();
  const auto mesh = std::make_shared<const TriangleMesh>(sphere_mesh);
  for (Link& l : links) {
    l.shapes[0].kind = Shape::Kind::kMesh;
    l.shapes[0].size = Eigen::Vector3d::Ones();
    l.shapes[0].mesh = mesh;
  }
  const RobotModel model("sphere meshes", std::move(links));
  const ClearanceModel clearance(model, 0.0);
  constexpr double kMargin = 1e-3, kGapAllowed = 2e-3;
  KinematicsData<double> k(model);
  std::vector<Clearance> out;
  std::mt19937 rng(6);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = RandomVector(3, 1.2, &rng), zero = Eigen::VectorXd::Zero(3);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    clearance.Compute(k, &out);
    for (size_t i = 0; i < out.size(); ++i) {
      const ClearancePair& p = clearance.pairs()[i];
      const auto placed = [&](int link) { return ShapeCentre_W(model, k, link); };
      if (p.link_b < 0) {
        double lowest = INFINITY;
        const Eigen::Matrix3d R_WG = ShapeRotation_W(model, k, p.link_a);
        for (const Eigen::Vector3d& v : sphere_mesh.vertices) lowest = std::min(lowest, (placed(p.link_a) + R_WG * v).z());
        EXPECT_LE(out[i].distance, lowest - kMargin + 1e-9) << p.Name(model) << " trial " << trial;
        EXPECT_GE(out[i].distance, lowest - kMargin - kGapAllowed) << p.Name(model) << " trial " << trial;
      } else {
        const double centres = (placed(p.link_a) - placed(p.link_b)).norm();
        EXPECT_LE(out[i].distance, centres - 2 * r_in - 2 * kMargin + 1e-9) << p.Name(model) << " trial " << trial;
        EXPECT_GE(out[i].distance, centres - 2 * r - 2 * (kMargin + kGapAllowed)) << p.Name(model) << " trial " << trial;
      }
    }
  }
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// Distance from a point to a box (full edges `size`, centred in its frame), ≥ 0 outside.
double PointBoxDistance(const Eigen::Vector3d& p_O, const Eigen::Vector3d& size) {
  const Eigen::Vector3d outside = (p_O.cwiseAbs() - 0.5 * size).cwiseMax(0.0);
  return outside.norm();
}

// The sphere robot in a cell, its base tilted and raised: distances to the
// floor, a box and a sphere obstacle match the analytic ones computed in the
// world (the box is 1 mm inflated, as every shape but a sphere).
TEST(LinkClearanceTest, CellObstaclesAndBasePoseMatchTheAnalyticDistances) {
  const double r = 0.1;
  const RobotModel model = MakeSphereRobot(r);
  Cell cell;
  Obstacle box;
  box.name = "wall";
  box.shape.kind = Shape::Kind::kBox;
  box.shape.size = Eigen::Vector3d(0.1, 3.0, 3.0);
  box.X_WO.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  box.X_WO.translation() = Eigen::Vector3d(1.6, 0.2, 1.0);
  Obstacle ball;
  ball.shape.kind = Shape::Kind::kSphere;
  ball.shape.size.setConstant(0.15);
  ball.X_WO.translation() = Eigen::Vector3d(-0.9, 0.4, 1.6);
  cell.obstacles = {box, ball};
  const BasePose base{{0.1, -0.2, 0.4, 0.2, -0.15, 0.7}};
  const ClearanceModel clearance(model, 0.01, cell, base);
  // Per link: wall, obstacle 1, ground (L0 and L1: their link pair is joined), and L2–L0.
  ASSERT_EQ(clearance.pairs().size(), 10u);
  const Eigen::Isometry3d X_WR = base.X_WR();
  KinematicsData<double> k(model);
  std::vector<Clearance> out;
  std::mt19937 rng(5);
  int n_checked = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::VectorXd q = RandomVector(3, 1.5, &rng), zero = Eigen::VectorXd::Zero(3);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    clearance.Compute(k, &out);
    for (size_t i = 0; i < out.size(); ++i) {
      const ClearancePair& p = clearance.pairs()[i];
      const Eigen::Vector3d c_W = X_WR * ShapeCentre_W(model, k, p.link_a);  // "W" of kinematics is R
      double expected = 0.0;
      if (p.link_b >= 0) {
        expected = (ShapeCentre_W(model, k, p.link_a) - ShapeCentre_W(model, k, p.link_b)).norm() - 2 * r;
      } else if (p.obstacle == 0) {
        const double d = PointBoxDistance(box.X_WO.inverse() * c_W, box.shape.size);
        if (d <= r + 2e-3) continue;  // overlapping: EPA's depth, not this formula
        expected = d - r - 1e-3;
        EXPECT_EQ(p.Name(model), model.link(p.link_a).name + "–wall");
      } else if (p.obstacle == 1) {
        expected = (c_W - ball.X_WO.translation()).norm() - r - 0.15;
        EXPECT_EQ(p.Other(model), "obstacle 1");
      } else {
        expected = c_W.z() - r;
      }
      EXPECT_NEAR(out[i].distance, expected, 1e-6) << p.Name(model) << " trial " << trial;
      ++n_checked;
    }
  }
  EXPECT_GT(n_checked, 250);
  // Without the floor, no ground pairs.
  cell.floor = false;
  EXPECT_EQ(ClearanceModel(model, 0.01, cell, base).pairs().size(), 7u);
}

// ∂d/∂q of an obstacle pair against central differences, the base mounted upside down.
TEST(LinkClearanceTest, ObstacleGradientMatchesFiniteDifferences) {
  const RobotModel model = MakeSphereRobot(0.1);
  Cell cell;
  Obstacle box;
  box.shape.kind = Shape::Kind::kBox;
  box.shape.size = Eigen::Vector3d(0.4, 0.3, 0.2);
  box.X_WO.translation() = Eigen::Vector3d(0.8, 0.7, 0.9);
  cell.obstacles = {box};
  cell.floor = false;
  const BasePose ceiling{{0, 0, 2.0, std::numbers::pi, 0, 0}};
  const ClearanceModel clearance(model, 0.01, cell, ceiling);
  KinematicsData<double> k(model), kp(model), km(model);
  std::mt19937 rng(9);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(3, 1.5, &rng);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    for (int i = 0; i < static_cast<int>(clearance.pairs().size()); ++i) {
      const Clearance c = clearance.ComputePair(k, i);
      if (c.distance < 0.01) continue;  // away from contact: a smooth distance
      const Eigen::VectorXd g = clearance.DistanceGradient(model, k, clearance.pairs()[static_cast<size_t>(i)], c);
      const double h = 1e-6;
      for (int j = 0; j < 3; ++j) {
        Eigen::VectorXd qp = q, qm = q;
        qp[j] += h, qm[j] -= h;
        ComputeKinematicsT<double>(model, qp, zero, zero, &kp);
        ComputeKinematicsT<double>(model, qm, zero, zero, &km);
        const double fd = (clearance.ComputePair(kp, i).distance - clearance.ComputePair(km, i).distance) / (2 * h);
        EXPECT_NEAR(g[j], fd, 1e-4) << clearance.pairs()[static_cast<size_t>(i)].Name(model) << " q" << j;
      }
    }
  }
}

TEST(LinkClearanceTest, AnInvalidCellIsRefusedNamingTheField) {
  const RobotModel model = MakeSphereRobot(0.1);
  Cell cell;
  cell.obstacles.resize(1);
  cell.obstacles[0].shape.kind = Shape::Kind::kSphere;  // size 0
  try {
    ClearanceModel(model, 0.01, cell);
    FAIL() << "accepted a sphere of radius 0";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("obstacles[0].size"), std::string::npos) << e.what();
  }
  cell.obstacles.assign(Cell::kMaxObstacles + 1, Obstacle{});
  for (Obstacle& o : cell.obstacles) o.shape.kind = Shape::Kind::kSphere, o.shape.size.setConstant(0.1);
  EXPECT_THROW(ClearanceModel(model, 0.01, cell), std::invalid_argument);
}

// The bounds the design's search prunes with never exceed the distance GJK
// measures: the bounding capsules (LowerBound) at random poses, and the
// reach bound d(q') ≥ d(q) − Σ reach_j |q'_j − q_j| between random pose
// pairs near and far apart: PUMA (cylinders, boxes), the UR10e-like arm
// (meshes) in a cell with a box and a sphere.
TEST(LinkClearanceTest, CapsuleAndReachBoundsNeverExceedTheGjkDistance) {
  Cell cell;
  Obstacle box, ball;
  box.shape.kind = Shape::Kind::kBox;
  box.shape.size = Eigen::Vector3d(0.1, 2.0, 1.0);
  box.X_WO.translation() = Eigen::Vector3d(0.6, 0.0, 0.5);
  ball.shape.kind = Shape::Kind::kSphere;
  ball.shape.size.setConstant(0.1);
  ball.X_WO.translation() = Eigen::Vector3d(-0.4, 0.3, 0.8);
  cell.obstacles = {box, ball};
  const RobotModel ur = LoadUrdfFile(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/ur10e_like/ur10e_like.urdf").model;
  const RobotModel panda = LoadUrdfFile(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/panda_like/panda_like.urdf").model;
  const RobotModel puma = MakePuma560();
  const RobotModel table_arm = LoadUrdfFile(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/table_arm/table_arm.urdf").model;
  int bounded = 0, checked = 0;
  for (const RobotModel* model : {&puma, &ur, &panda, &table_arm}) {
    const ClearanceModel clearance(*model, 0.01, model == &ur ? cell : Cell());
    const int n = model->n_dof();
    KinematicsData<double> k(*model), k2(*model);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    std::mt19937 rng(11);
    for (int pose = 0; pose < 150; ++pose) {
      const Eigen::VectorXd q = RandomVector(n, 3.0, &rng);
      const Eigen::VectorXd q2 = q + RandomVector(n, pose % 2 ? 0.05 : 1.0, &rng);
      ComputeKinematicsT<double>(*model, q, zero, zero, &k);
      ComputeKinematicsT<double>(*model, q2, zero, zero, &k2);
      for (int i = 0; i < static_cast<int>(clearance.pairs().size()); ++i) {
        const double d = clearance.ComputePair(k, i).distance, d2 = clearance.ComputePair(k2, i).distance;
        const double bound = clearance.LowerBound(k, i);
        EXPECT_LE(bound, d + 1e-9) << clearance.pairs()[static_cast<size_t>(i)].Name(*model);
        bounded += bound > 0.0;
        double moved = d;
        for (int j = 0; j < n; ++j) moved -= clearance.pairs()[static_cast<size_t>(i)].reach[static_cast<size_t>(j)] * std::abs(q2[j] - q[j]);
        EXPECT_LE(moved, d2 + 1e-7) << clearance.pairs()[static_cast<size_t>(i)].Name(*model);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_GT(bounded, checked / 4);  // the capsules are tight enough to bound most pairs above 0
}

// ---- The robot file's fixed links and contact at q = 0 (issue 35) ----

// The least of the exact point–box distances (negative inside) from the 8
// corners of a box (edges `size`, centre c_W, axes R_WG) to an axis-aligned box.
double CornersToBox(const Eigen::Matrix3d& R_WG, const Eigen::Vector3d& c_W, const Eigen::Vector3d& size,
                    const Eigen::Vector3d& box_centre_W, const Eigen::Vector3d& box_size) {
  double least = std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
    const Eigen::Vector3d p = c_W + R_WG * (0.5 * sign.cwiseProduct(size)) - box_centre_W;
    const Eigen::Vector3d d = p.cwiseAbs() - 0.5 * box_size;
    least = std::min(least, d.maxCoeff() > 0.0 ? d.cwiseMax(0.0).norm() : d.maxCoeff());
  }
  return least;
}

// An arm on a pedestal on a table (tests/data/table_arm): the root link and
// the links fixed to it are the model's ground, and obstacles to every link
// not hinged on them; the distances to the table are the exact ones (less
// the 1 mm inflation of each shape), inside it too; a fixed link out of reach
// (a lamp 5 m away) makes no pair.
TEST(LinkClearanceTest, FixedLinksOfTheRobotFileAreObstacles) {
  const RobotModel model = LoadUrdfFile(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/table_arm/table_arm.urdf").model;
  ASSERT_EQ(model.ground().size(), 3u);
  EXPECT_EQ(model.ground()[0].name, "table");
  EXPECT_EQ(model.ground()[1].name, "lamp");  // depth first, in the file's order of joints
  EXPECT_EQ(model.ground()[2].name, "pedestal");
  const ClearanceModel clearance(model, 0.02);
  std::vector<std::string> names;
  for (const ClearancePair& p : clearance.pairs()) names.push_back(p.Name(model));
  EXPECT_EQ(names, (std::vector<std::string>{"l1–ground", "l2–ground", "l2–table", "l2–pedestal", "l3–ground",
                                             "l3–table", "l3–pedestal", "l3–l1"}));
  const std::vector<std::string> excluded = {
      "l1–table: joined by joint 'j1'", "l1–lamp: joined by joint 'j1'", "l1–pedestal: joined by joint 'j1'",
      "l2–lamp: out of reach", "l2–l1: joined by joint 'j2'", "l3–lamp: out of reach", "l3–l2: joined by joint 'j3'"};
  ASSERT_EQ(clearance.excluded().size(), excluded.size());
  for (size_t i = 0; i < excluded.size(); ++i) {
    EXPECT_EQ(clearance.excluded()[i].rfind(excluded[i], 0), 0u) << clearance.excluded()[i];
  }
  const int l2_table = 2, l3_table = 5;
  EXPECT_EQ(clearance.pairs()[l2_table].other(), ClearanceOther::kGroundLink);
  // l2 swung down by j2 into the table, and l3 folded down into it: the
  // box corners (own kinematics: l2 turns about y at (0, 0, 0.75)) against the table.
  const Eigen::Vector3d table_centre(0, 0, 0.25), table_size(2.0, 2.0, 0.5);
  KinematicsData<double> k(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  int inside = 0;
  for (const double q2 : {1.2, 1.8, 2.2, 2.5}) {
    for (const double q3 : {-1.5, 0.0, 1.5}) {
      const Eigen::Vector3d q(0.3, q2, q3);
      const Eigen::Matrix3d R_W2 = Eigen::AngleAxisd(q[0], Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                   Eigen::AngleAxisd(q[1], Eigen::Vector3d::UnitY()).toRotationMatrix();
      const Eigen::Matrix3d R_W3 = R_W2 * Eigen::AngleAxisd(q[2], Eigen::Vector3d::UnitY()).toRotationMatrix();
      const Eigen::Vector3d o2(0, 0, 0.75), o3 = o2 + R_W2 * Eigen::Vector3d(0, 0, 0.4);
      const double exact2 = CornersToBox(R_W2, o2 + R_W2 * Eigen::Vector3d(0, 0, 0.2), {0.06, 0.06, 0.4}, table_centre, table_size);
      const double exact3 = CornersToBox(R_W3, o3 + R_W3 * Eigen::Vector3d(0, 0, 0.15), {0.05, 0.05, 0.3}, table_centre, table_size);
      ComputeKinematicsT<double>(model, q, zero, zero, &k);
      // Over the table top, the nearest point of a box is a corner, and so is
      // the deepest of a box poking into it. Deeper in, the table's nearest
      // face may be another one: separating takes at least the corners' depth.
      const double d2 = clearance.ComputePair(k, l2_table).distance, d3 = clearance.ComputePair(k, l3_table).distance;
      if (exact2 > -0.05) EXPECT_NEAR(d2, exact2 - 2e-3, 1e-4) << q.transpose();
      if (exact3 > -0.05) EXPECT_NEAR(d3, exact3 - 2e-3, 1e-4) << q.transpose();
      EXPECT_LE(d2, exact2 - 2e-3 + 1e-4) << q.transpose();
      EXPECT_LE(d3, exact3 - 2e-3 + 1e-4) << q.transpose();
      inside += (exact2 < -0.02) + (exact3 < -0.02);
    }
  }
  EXPECT_GE(inside, 4);  // poses inside the table are among them
}

// A first link turning about the vertical, touching a post at q = 0 (a SCARA
// beside a column): its pair is kept, held at its distance at q = 0, and
// turning towards the post violates it; its distance to the floor, which no
// such turn changes, is the only pair left out.
TEST(LinkClearanceTest, AVerticalJointTouchingAnObstacleAtHomeIsHeldThere) {
  Link arm;
  arm.name = "arm";
  arm.inertia.mass = 1.0;
  arm.inertia.I_Bcm_B = 0.01 * Eigen::Matrix3d::Identity();
  Shape bar;
  bar.kind = Shape::Kind::kBox;
  bar.size = Eigen::Vector3d(0.5, 0.1, 0.1);
  bar.X_BG.translation() = Eigen::Vector3d(0.25, 0, 0.05);  // resting on the floor
  arm.shapes.push_back(bar);
  const RobotModel model("scara", {arm});
  Cell cell;
  Obstacle post;
  post.name = "post";
  post.shape.kind = Shape::Kind::kCylinder;
  post.shape.size = Eigen::Vector3d(0.05, 0.05, 1.0);
  post.X_WO.translation() = Eigen::Vector3d(0.4, 0.1, 0.5);  // its side touches the bar's at y = 0.05
  cell.obstacles = {post};
  const ClearanceModel clearance(model, 0.01, cell);
  ASSERT_EQ(clearance.pairs().size(), 1u);
  ASSERT_EQ(clearance.excluded().size(), 1u);
  EXPECT_EQ(clearance.excluded()[0].rfind("arm–ground: on the ground at q = 0", 0), 0u) << clearance.excluded()[0];
  const ClearancePair& pair = clearance.pairs()[0];
  EXPECT_EQ(pair.Name(model), "arm–post");
  EXPECT_NEAR(pair.home_distance, -2e-3, 1e-4);  // touching: the two 1 mm inflations overlap
  EXPECT_DOUBLE_EQ(pair.minimum, pair.home_distance - ClearanceModel::kContactTolerance);
  KinematicsData<double> k(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  for (const double q : {-0.3, -0.1, 0.1, 0.3}) {
    ComputeKinematicsT<double>(model, Eigen::VectorXd::Constant(1, q), zero, zero, &k);
    const double d = clearance.ComputePair(k, 0).distance;
    // Turning away opens a gap; turning towards the post sweeps the bar into it.
    if (q < 0) EXPECT_GT(d, pair.minimum + 0.01) << q;
    if (q > 0) EXPECT_LT(d, pair.minimum - 0.01) << q;
  }
  // On a table top instead (a base standing on it, no floor): turning keeps
  // the distance there, which EPA measures the same to kContactTolerance.
  Obstacle table;
  table.name = "table";
  table.shape.kind = Shape::Kind::kBox;
  table.shape.size = Eigen::Vector3d(2.0, 2.0, 0.5);
  table.X_WO.translation() = Eigen::Vector3d(0.1, -0.2, -0.25);
  cell.obstacles = {table};
  cell.floor = false;
  const ClearanceModel on_table(model, 0.01, cell);
  ASSERT_EQ(on_table.pairs().size(), 1u);
  const double minimum = on_table.pairs()[0].minimum;
  for (int step = 0; step <= 600; ++step) {
    ComputeKinematicsT<double>(model, Eigen::VectorXd::Constant(1, -3.0 + 0.01 * step), zero, zero, &k);
    EXPECT_NEAR(on_table.ComputePair(k, 0).distance, on_table.pairs()[0].home_distance, 1e-9) << step;
  }
  EXPECT_LT(minimum, on_table.pairs()[0].home_distance);
}

// The KUKA LWR4+ file (../shared/data/kuka_lwr4, skipped when absent) stands
// on a 1.2 × 0.74 × 1.0 m table, its root link `box`: every link above the
// first is kept from it, and a pose folding the forearm down beside the base
// puts a link inside it, which the clearance sees.
TEST(LinkClearanceTest, KukaLwr4IsKeptFromItsTable) {
  const std::filesystem::path path = std::filesystem::path(IDBENCH_SOURCE_DIR) /
                                     "../shared/data/kuka_lwr4/lwr_description/urdf/kuka_lwr4.urdf";
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << path << " is absent (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  }
  const RobotModel model = LoadUrdfFile(path.string()).model;
  ASSERT_GE(model.ground().size(), 1u);
  EXPECT_EQ(model.ground()[0].name, "box");
  const ClearanceModel clearance(model, 0.0);
  std::vector<int> table_pairs;  // per link, its pair with the table (−1: none)
  for (int a = 0; a < model.n_links(); ++a) {
    table_pairs.push_back(-1);
    for (size_t i = 0; i < clearance.pairs().size(); ++i) {
      const ClearancePair& p = clearance.pairs()[i];
      if (p.link_a == a && p.other() == ClearanceOther::kGroundLink && p.Other(model) == "box") table_pairs[a] = static_cast<int>(i);
    }
  }
  EXPECT_EQ(table_pairs[0], -1);  // lwr_1_link turns on the base
  for (int a = 1; a < 7; ++a) EXPECT_GE(table_pairs[a], 0) << model.link(a).name;
  // Shoulder down to horizontal, elbow folded down: the wrist's frame origin
  // (own check: its height against the table top at z = 1 m, over the table).
  const Eigen::VectorXd q = (Eigen::VectorXd(7) << 0, -1.5708, 0, 1.5708, 0, 0, 0).finished();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(7);
  KinematicsData<double> k(model);
  ComputeKinematicsT<double>(model, q, zero, zero, &k);
  const Eigen::Vector3d p_wrist = k.p_WBo_W[5];
  ASSERT_LT(p_wrist.z(), 1.0 - 0.05) << p_wrist.transpose();
  ASSERT_LT(std::abs(p_wrist.x()), 0.6) << p_wrist.transpose();
  ASSERT_LT(std::abs(p_wrist.y()), 0.37) << p_wrist.transpose();
  EXPECT_LT(clearance.ComputePair(k, table_pairs[5]).distance, -(1.0 - p_wrist.z()) + 0.05);
}

}  // namespace
}  // namespace idbench
