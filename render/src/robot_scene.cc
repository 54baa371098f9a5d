#include "idbench/render/robot_scene.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace idbench {
namespace {

const Eigen::Vector3f kHingeColor(0.16f, 0.16f, 0.18f);
const Eigen::Vector3f kPedestalColor(0.52f, 0.52f, 0.54f);

// The thickness of a link for sizing its hinge marker [m]: radius of its
// first shape (half the smallest edge of a box, the middle one of a mesh's
// bounding box); `fallback` without shapes.
double LinkRadius(const Link& link, double fallback) {
  if (link.shapes.empty()) return fallback;
  const Shape& s = link.shapes.front();
  if (s.kind == Shape::Kind::kBox) return 0.5 * s.size.minCoeff();
  if (s.kind == Shape::Kind::kMesh && s.mesh != nullptr) {
    Eigen::Vector3d edges = s.mesh->hi_G - s.mesh->lo_G;
    std::sort(edges.data(), edges.data() + 3);
    return 0.5 * edges[1];
  }
  return s.size.x();
}

// Radius of the stand-in rods of links without shapes: 4 % of the span of the
// joint origins (5 cm for a robot whose joints all coincide) [m].
double StandInRadius(const RobotModel& model, const RobotData& data) {
  Eigen::Vector3d lo = data.p_WBo_W.front(), hi = lo;
  for (const Eigen::Vector3d& p : data.p_WBo_W) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double span = (hi - lo).norm();
  return span > 0.0 ? 0.04 * span : 0.05;
}

// Direction of the link's first cylinder axis in B, or zero.
Eigen::Vector3d LinkAxis_B(const Link& link) {
  if (link.shapes.empty() || link.shapes.front().kind != Shape::Kind::kCylinder) return Eigen::Vector3d::Zero();
  return link.shapes.front().X_BG.linear().col(2);
}

// The rotation taking z onto the unit vector a.
Eigen::Matrix3d RotationZTo(const Eigen::Vector3d& a) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a).toRotationMatrix();
}

}  // namespace

std::vector<Eigen::Vector3d> Scene::BoundingPoints() const {
  std::vector<Eigen::Vector3d> points;
  points.reserve(8 * primitives.size());
  for (const ScenePrimitive& p : primitives) {
    Eigen::Vector3d lo_G, hi_G;
    if (p.kind == Shape::Kind::kMesh) {
      lo_G = p.mesh->lo_G.cwiseProduct(p.size), hi_G = p.mesh->hi_G.cwiseProduct(p.size);
    } else {
      hi_G = p.kind == Shape::Kind::kBox        ? 0.5 * p.size
             : p.kind == Shape::Kind::kCylinder ? Eigen::Vector3d(p.size.x(), p.size.x(), 0.5 * p.size.z())
                                                : Eigen::Vector3d::Constant(p.size.x());
      lo_G = -hi_G;
    }
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p_G(corner & 1 ? hi_G.x() : lo_G.x(), corner & 2 ? hi_G.y() : lo_G.y(),
                                corner & 4 ? hi_G.z() : lo_G.z());
      points.push_back(p.X_WG * p_G);
    }
  }
  return points;
}

Eigen::Vector3f LinkColor(int link) {
  static const std::array<Eigen::Vector3f, 6> kPalette{
      Eigen::Vector3f(0.20f, 0.42f, 0.74f), Eigen::Vector3f(0.91f, 0.50f, 0.13f),
      Eigen::Vector3f(0.22f, 0.63f, 0.33f), Eigen::Vector3f(0.80f, 0.22f, 0.22f),
      Eigen::Vector3f(0.55f, 0.33f, 0.76f), Eigen::Vector3f(0.10f, 0.62f, 0.66f)};
  return kPalette[static_cast<size_t>(link) % kPalette.size()];
}

const Eigen::Vector3f kObstacleColor(0.74f, 0.69f, 0.60f);

std::vector<Eigen::Vector3d> CellPointsNearRobot(const Scene& cell, const std::vector<Eigen::Vector3d>& robot_points) {
  std::vector<Eigen::Vector3d> points;
  if (cell.primitives.empty() || robot_points.empty()) return points;
  Eigen::Vector3d lo = robot_points.front(), hi = lo;
  for (const Eigen::Vector3d& p : robot_points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector3d widen = 0.5 * (hi - lo);
  for (const Eigen::Vector3d& p : cell.BoundingPoints()) points.push_back(p.cwiseMax(lo - widen).cwiseMin(hi + widen));
  return points;
}

void AddCellObstacles(const Cell& cell, Scene* scene) {
  for (const Obstacle& o : cell.obstacles) {
    if (o.shape.kind == Shape::Kind::kMesh && o.shape.mesh == nullptr) continue;
    // A mesh obstacle's triangles are already scaled (cell.h): no scale on top.
    const Eigen::Vector3d size = o.shape.kind == Shape::Kind::kMesh ? Eigen::Vector3d::Ones() : o.shape.size;
    scene->primitives.push_back({o.shape.kind, size, o.shape.mesh, o.X_WO, kObstacleColor});
  }
}

Scene BuildRobotScene(const RobotModel& model, const RobotData& data, const Eigen::Isometry3d& X_WR) {
  Scene scene;
  const bool mounted = !X_WR.isApprox(Eigen::Isometry3d::Identity(), 1e-12);
  const double stand_in = StandInRadius(model, data);
  // The ground links (a table, a pedestal the arm stands on), in R; drawn
  // from their visual shapes, or the collision ones when they have none.
  bool has_ground_shapes = false;
  for (const GroundLink& link : model.ground()) {
    for (const Shape& shape : link.shapes.empty() ? link.CollisionShapes() : link.shapes) {
      if (shape.kind == Shape::Kind::kMesh && shape.mesh == nullptr) continue;
      scene.primitives.push_back({shape.kind, shape.kind == Shape::Kind::kMesh ? Eigen::Vector3d::Ones() : shape.size,
                                  shape.mesh, shape.X_BG, kPedestalColor});
      has_ground_shapes = true;
    }
  }
  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    X_WB.linear() = data.R_WB[static_cast<size_t>(i)];
    X_WB.translation() = data.p_WBo_W[static_cast<size_t>(i)];
    // The link's own shapes.
    for (const Shape& shape : link.shapes) {
      if (shape.kind == Shape::Kind::kMesh && shape.mesh == nullptr) continue;
      ScenePrimitive p{shape.kind, shape.kind == Shape::Kind::kMesh ? Eigen::Vector3d::Ones() : shape.size,
                       shape.mesh, X_WB * shape.X_BG, LinkColor(i)};
      scene.primitives.push_back(p);
    }
    // Without shapes: rods to the children's joints, or a ball at the COM.
    if (link.shapes.empty()) {
      bool has_child = false;
      for (int c = i + 1; c < model.n_links(); ++c) {
        if (model.link(c).parent != i) continue;
        has_child = true;
        const Eigen::Vector3d a = X_WB.translation(), b = data.p_WBo_W[static_cast<size_t>(c)];
        if ((b - a).norm() < 1e-9) continue;
        ScenePrimitive rod{Shape::Kind::kCylinder, Eigen::Vector3d(stand_in, stand_in, (b - a).norm()), nullptr,
                           Eigen::Isometry3d::Identity(), LinkColor(i)};
        rod.X_WG.linear() = RotationZTo((b - a).normalized());
        rod.X_WG.translation() = 0.5 * (a + b);
        scene.primitives.push_back(rod);
      }
      if (!has_child) {
        ScenePrimitive ball{Shape::Kind::kSphere, Eigen::Vector3d::Constant(1.5 * stand_in), nullptr,
                            Eigen::Isometry3d::Identity(), LinkColor(i)};
        ball.X_WG.translation() = X_WB * link.inertia.p_BoBcm_B;
        scene.primitives.push_back(ball);
      }
    }
    // A grey pedestal from the ground (z = 0) up to a base joint above it,
    // unless the robot file has its own.
    const double base_height = link.parent < 0 ? X_WB.translation().z() : 0.0;
    if (!mounted && !has_ground_shapes && base_height > 0.05 && LinkRadius(link, stand_in) > 0.0) {
      ScenePrimitive pedestal;
      pedestal.kind = Shape::Kind::kCylinder;
      pedestal.color = kPedestalColor;
      const double r = std::max(1.5 * LinkRadius(link, stand_in), 0.12 * base_height);
      pedestal.size = Eigen::Vector3d(r, r, base_height);
      pedestal.X_WG.translation() = Eigen::Vector3d(X_WB.translation().x(), X_WB.translation().y(), 0.5 * base_height);
      scene.primitives.push_back(pedestal);
    }
    // The hinge at the link's origin, sized from the two links it joins.
    const double r_child = LinkRadius(link, stand_in);
    const double r_parent = link.parent >= 0 ? LinkRadius(model.link(link.parent), stand_in) : 0.0;
    const double r_max = std::max(r_child, r_parent);
    if (r_max <= 0.0) continue;
    const double r_min = r_parent > 0.0 && r_child > 0.0 ? std::min(r_child, r_parent) : r_max;
    const Eigen::Vector3d axis_W = data.axis_W[static_cast<size_t>(i)];
    const bool along_link = std::abs(LinkAxis_B(link).dot(link.axis_J)) > 0.7;
    ScenePrimitive hinge;
    hinge.kind = Shape::Kind::kCylinder;
    hinge.color = kHingeColor;
    hinge.X_WG.linear() = RotationZTo(axis_W);
    hinge.X_WG.translation() = X_WB.translation();
    if (along_link) {
      // A collar just wider than both links, straddling the joint.
      hinge.size = Eigen::Vector3d(1.1 * r_max, 1.1 * r_max, 0.35 * r_min);
    } else {
      // A pin through the joint, sticking out of the wider link on both sides.
      hinge.size = Eigen::Vector3d(0.45 * r_min, 0.45 * r_min, 2.0 * r_max + 0.5 * r_min);
    }
    scene.primitives.push_back(hinge);
  }
  // Everything above is in R: into W.
  if (mounted) {
    for (ScenePrimitive& p : scene.primitives) p.X_WG = X_WR * p.X_WG;
  }
  return scene;
}

}  // namespace idbench
