// The cell around a robot (a scene, --scene): the floor (the plane z = 0 of the world W, on by
// default) and fixed obstacles — boxes, cylinders, spheres and meshes — each
// with its pose in W. Link clearance (link_clearance.h) keeps the links away
// from each; the robot's base is placed in W by a BasePose (base_pose.h).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench {

struct Obstacle {
  std::string name;  // as the scene names it; "" reads as "obstacle <index>"
  // kind and size as a link's Shape (robot_model.h): box full edges; cylinder
  // (radius, radius, length) along z of O; sphere (r, r, r); mesh: its scale,
  // the triangles in `shape.mesh` (in O, scaled). shape.X_BG is unused.
  Shape shape;
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  // obstacle frame O in the world
};

struct Cell {
  static constexpr int kMaxObstacles = 64;  // each is checked against every link at every instant

  bool floor = true;  // the plane z = 0 of W (links keep the clearance above it)
  std::vector<Obstacle> obstacles;

  // At most kMaxObstacles; sizes finite and > 0 (at most 100 m), meshes with
  // vertices, poses finite and rigid. *why names the field: "obstacles[2].size".
  bool IsValid(std::string* why) const;
  // obstacles[i].name, or "obstacle <i>" when it has none.
  std::string ObstacleName(int i) const;
};

}  // namespace idbench
