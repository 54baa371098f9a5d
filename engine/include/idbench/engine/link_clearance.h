// Clearance of a robot's links: the distance between the shapes of two links
// that no joint connects, and from each link to the ground (the plane z = 0
// of W), by Bullet's GJK (and EPA when shapes overlap: negative distance) on
// each link's collision shapes (Link::CollisionShapes: its <collision>
// geometry, else what is drawn): cylinders, boxes, spheres, and meshes as
// their convex hulls. Every shape but a sphere is checked 1 mm inflated (its
// Minkowski sum with a 1 mm ball), so distances are up to 1 mm short per
// shape: conservative. A hull of more than 256 points (GJK's cost grows with
// them) is replaced by its support points in 256 directions, grown by how far
// the full hull reaches beyond them (~2 mm for a 10 cm sphere mesh): still
// conservative.
//
// Pairs that touch by construction are left out: parent and child, and pairs
// already closer than `min_clearance` at the home pose q = 0 (a base resting
// on the ground, wrist links sharing a centre); ClearanceModel::excluded()
// lists them with the reason.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

struct ClearancePair {
  int link_a = 0;
  int link_b = -1;  // −1: the ground
  std::string Name(const RobotModel& model) const;  // "link2–link5", "link4–ground"
};

struct Clearance {
  double distance = 0.0;                             // [m]; < 0 when the shapes overlap
  Eigen::Vector3d p_a_W = Eigen::Vector3d::Zero();   // closest point on link a
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();    // unit, from b towards a: d grows along it
};

class ClearanceModel {
 public:
  // Throws std::invalid_argument if min_clearance < 0.
  ClearanceModel(const RobotModel& model, double min_clearance);
  ~ClearanceModel();
  ClearanceModel(ClearanceModel&&) noexcept;
  ClearanceModel& operator=(ClearanceModel&&) noexcept;

  double min_clearance() const { return min_clearance_; }
  const std::vector<ClearancePair>& pairs() const { return pairs_; }
  const std::vector<std::string>& excluded() const { return excluded_; }

  // The clearance of every pair at the link poses in k (one entry per pair).
  // With at_least (one value per pair), a pair whose shapes' bounding spheres
  // are at least that far apart gets that lower bound instead (no GJK; its
  // points and normal are unset): enough to track a minimum over instants.
  void Compute(const KinematicsData<double>& k, std::vector<Clearance>* out,
               const std::vector<double>* at_least = nullptr) const;

  // ∂distance/∂q (n_dof) of a pair from its Clearance: the closest point on a
  // moves with the joints of a's chain, the one on b with b's (ground: fixed).
  Eigen::VectorXd DistanceGradient(const RobotModel& model, const KinematicsData<double>& k,
                                   const ClearancePair& pair, const Clearance& c) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double min_clearance_ = 0.0;
  std::vector<ClearancePair> pairs_;
  std::vector<std::string> excluded_;
};

}  // namespace idbench
