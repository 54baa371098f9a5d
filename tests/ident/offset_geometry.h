// A robot file whose shapes are not placed in the frames of its inertials, as
// the Stäubli TX40's published MDH URDF (rendered, its links float apart):
// each link's only shape is a box beside its centre of mass.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"

namespace idbench::testing {

// The model with each link's shapes replaced by one cube of `edge` [m]
// centred at its centre of mass + offset_B [m] (link frame B).
inline RobotModel WithOffsetShapes(const RobotModel& model, const Eigen::Vector3d& offset_B, double edge) {
  std::vector<Link> links = model.links();
  for (Link& link : links) {
    Shape box;
    box.kind = Shape::Kind::kBox;
    box.size = Eigen::Vector3d::Constant(edge);
    box.X_BG.translation() = link.inertia.p_BoBcm_B + offset_B;
    link.shapes = {box};
    link.collision_shapes.clear();
  }
  return RobotModel(model.name(), std::move(links), model.gravity_W());
}

// The model with each link's centre of mass moved to the centre of its first
// shape (inertia about it kept): a file whose centres of mass agree with its
// shapes while the robot's (the log's) do not.
inline RobotModel WithComAtShapes(const RobotModel& model) {
  std::vector<Link> links = model.links();
  for (Link& link : links) link.inertia.p_BoBcm_B = link.shapes.front().X_BG.translation();
  return RobotModel(model.name(), std::move(links), model.gravity_W());
}

// Adds N(0, σ²) to every torque; deterministic per seed.
inline JointLog WithTorqueNoise(JointLog log, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  for (Eigen::Index s = 0; s < log.tau.rows(); ++s)
    for (Eigen::Index j = 0; j < log.tau.cols(); ++j) log.tau(s, j) += normal(rng);
  return log;
}

}  // namespace idbench::testing
