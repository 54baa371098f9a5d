// What the renderer draws: coloured primitives posed in the world frame W,
// built from a robot model at one joint configuration. Plain data, no GL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "idbench/engine/cell.h"
#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

struct ScenePrimitive {
  Shape::Kind kind = Shape::Kind::kCylinder;
  // As Shape::size: cylinder (r, r, length) along z of G; box edges; sphere
  // (r, r, r) [m]; mesh: a scale applied on top of the mesh's vertices.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  std::shared_ptr<const TriangleMesh> mesh;  // kMesh
  Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();  // primitive frame G in W
  Eigen::Vector3f color = Eigen::Vector3f::Ones();         // linear RGB in [0, 1]
};

struct Scene {
  std::vector<ScenePrimitive> primitives;

  // Corners of every primitive's bounding box in W (8 per primitive) [m]:
  // what a camera must keep in view.
  std::vector<Eigen::Vector3d> BoundingPoints() const;
};

// Link colours: saturated, distinct for neighbours, cycling.
Eigen::Vector3f LinkColor(int link);

// The robot at the pose in `data` (ComputeKinematics done): every link's
// shapes in its colour (a link without any, e.g. whose meshes were not found:
// a rod from its joint to each child's joint, or a ball at its centre of mass
// for the last link), and a dark marker at every hinge: a pin along the
// axis sticking out of both links, or a collar when the axis runs along the
// link (so it would hide inside a pin); a grey pedestal under a base joint
// that sits above the ground z = 0. X_WR places the robot's base frame R
// (the model's world, where `data` holds the poses) in the drawn world W (a
// mounting, base_pose.h); a mounted robot (X_WR not the identity) gets no
// pedestal: the mounting says what holds it.
Scene BuildRobotScene(const RobotModel& model, const RobotData& data,
                      const Eigen::Isometry3d& X_WR = Eigen::Isometry3d::Identity());

// The colour of the cell's obstacles: a neutral sand, apart from the links'.
extern const Eigen::Vector3f kObstacleColor;

// The cell's obstacles (cell.h) as primitives at their poses in W, in
// kObstacleColor, appended to *scene. The floor is the renderer's own.
void AddCellObstacles(const Cell& cell, Scene* scene);

// What a camera keeps in view of the obstacles `cell` (AddCellObstacles'
// primitives) beside a robot whose bounding points are robot_points: the
// corners of their bounding boxes clipped to the robot's box widened by half
// its size, so that a big table or wall does not shrink the robot in view.
// None when either is empty.
std::vector<Eigen::Vector3d> CellPointsNearRobot(const Scene& cell, const std::vector<Eigen::Vector3d>& robot_points);

}  // namespace idbench
