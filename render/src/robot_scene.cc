#include "idbench/render/robot_scene.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace idbench {
namespace {

const Eigen::Vector3f kHingeColor(0.16f, 0.16f, 0.18f);
const Eigen::Vector3f kPedestalColor(0.52f, 0.52f, 0.54f);

// The thickness of a link for sizing its hinge marker [m]: radius of its
// first shape (half the smaller cross-section edge of a box); 0 without shapes.
double LinkRadius(const Link& link) {
  if (link.shapes.empty()) return 0.0;
  const Shape& s = link.shapes.front();
  if (s.kind == Shape::Kind::kBox) return 0.5 * std::min({s.size.x(), s.size.y(), s.size.z()});
  return s.size.x();
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
    const Eigen::Vector3d half = p.kind == Shape::Kind::kBox ? 0.5 * p.size
                                 : p.kind == Shape::Kind::kCylinder
                                     ? Eigen::Vector3d(p.size.x(), p.size.x(), 0.5 * p.size.z())
                                     : Eigen::Vector3d::Constant(p.size.x());
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p_G((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                (corner & 4 ? 1 : -1) * half.z());
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

Scene BuildRobotScene(const RobotModel& model, const RobotData& data) {
  Scene scene;
  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    X_WB.linear() = data.R_WB[static_cast<size_t>(i)];
    X_WB.translation() = data.p_WBo_W[static_cast<size_t>(i)];
    // The link's own shapes.
    for (const Shape& shape : link.shapes) {
      scene.primitives.push_back({shape.kind, shape.size, X_WB * shape.X_BG, LinkColor(i)});
    }
    // A grey pedestal from the ground (z = 0) up to a base joint above it.
    const double base_height = link.parent < 0 ? X_WB.translation().z() : 0.0;
    if (base_height > 0.05 && LinkRadius(link) > 0.0) {
      ScenePrimitive pedestal;
      pedestal.kind = Shape::Kind::kCylinder;
      pedestal.color = kPedestalColor;
      const double r = std::max(1.5 * LinkRadius(link), 0.12 * base_height);
      pedestal.size = Eigen::Vector3d(r, r, base_height);
      pedestal.X_WG.translation() = Eigen::Vector3d(X_WB.translation().x(), X_WB.translation().y(), 0.5 * base_height);
      scene.primitives.push_back(pedestal);
    }
    // The hinge at the link's origin, sized from the two links it joins.
    const double r_child = LinkRadius(link);
    const double r_parent = link.parent >= 0 ? LinkRadius(model.link(link.parent)) : 0.0;
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
  return scene;
}

}  // namespace idbench
