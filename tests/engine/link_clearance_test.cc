#include "idbench/engine/link_clearance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
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
  int bounded = 0, checked = 0;
  for (const RobotModel* model : {&puma, &ur, &panda}) {
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

}  // namespace
}  // namespace idbench
