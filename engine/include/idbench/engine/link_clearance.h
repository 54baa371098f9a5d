// Clearance of a robot's links: the distance between the shapes of two links
// that no joint connects, from each link to the floor (the plane z = 0 of the
// world), to each obstacle of the cell (cell.h) and to each ground link of the
// robot (RobotModel::ground(): the table or pedestal of its file), by Bullet's GJK (and EPA when shapes overlap: negative distance) on
// each link's collision shapes (Link::CollisionShapes: its <collision>
// geometry, else what is drawn): cylinders, boxes, spheres, and meshes as
// their convex hulls. Every shape but a sphere is checked 1 mm inflated (its
// Minkowski sum with a 1 mm ball), so distances are up to 1 mm short per
// shape: conservative. A hull of more than 256 points (GJK's cost grows with
// them) is replaced by its support points in 256 directions, grown by how far
// the full hull reaches beyond them (~2 mm for a 10 cm sphere mesh): still
// conservative.
//
// Each pair is held at least its own minimum distance apart: min_clearance,
// or, for a pair already closer than that at the home pose q = 0 (the robot
// file's zero pose), its distance there (less 1 µm, kHomeTolerance; less
// kContactTolerance when two shapes touch or overlap there, a penetration
// depth by EPA) — it may not get closer than it starts. No pair is dropped for being
// close. Only pairs whose distance cannot fall below their minimum are left
// out, and ClearanceModel::excluded() names each once with the reason:
//  - parent and child (joined by a joint), and a link hinged on the ground
//    (its parent is −1) with every ground link;
//  - two moving links whose shapes touch or overlap at q = 0 (distance ≤ 0
//    with the 1 mm inflation: a true gap under 2 mm; wrist links sharing a
//    centre);
//  - a link on the floor at q = 0 that no joint can raise or lower (every
//    joint from the ground to it turns about the vertical: a base on the
//    floor), whose distance to the floor no motion changes. A link on the
//    floor at q = 0 that joints can move keeps its distance there as its
//    minimum;
//  - a ground link out of a link's reach: farther from the origin of the
//    link's chain than any point of the link can be, plus min_clearance.
// A link touching an obstacle at q = 0 that no joint raises (a base standing
// on a table top, a first link beside a post) is held at its distance there:
// turning about the vertical may still sweep it into the obstacle. Every
// other obstacle pair keeps min_clearance, never its distance at q = 0 (the
// cell is not the robot: a pose inside it is a violation). A ground link is
// a part of the robot: its pairs are held as those between links.
//
// Frames. Kinematics run in the robot's base frame R (what RobotModel and
// KinematicsData call W); the cell is given in the world and placed in R by
// the base pose: the floor becomes the plane n_R·p + h = 0 with n_R = R_WRᵀ·ẑ,
// an obstacle's pose X_RO = X_WR⁻¹·X_WO. Points and normals of a Clearance are
// in R. Obstacles are inflated by 1 mm as the links' shapes are.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/cell.h"

namespace idbench {

// What a pair's link a is kept from.
enum class ClearanceOther {
  kLink,        // another moving link (ClearancePair::link_b)
  kFloor,       // the floor (the plane z = 0 of the world)
  kObstacle,    // an obstacle of the cell (ClearancePair::obstacle)
  kGroundLink,  // a ground link of the robot (ClearancePair::ground_link)
};

struct ClearancePair {
  int link_a = 0;
  int link_b = -1;       // −1: the floor, an obstacle or a ground link (not a moving link)
  int obstacle = -1;     // with link_b = −1: the scene's obstacle index
  int ground_link = -1;  // with link_b = −1: the index in RobotModel::ground(); both −1: the floor
  std::string obstacle_name;  // Cell::ObstacleName(obstacle)
  ClearanceOther other() const;
  double minimum = 0.0;        // [m] the least distance allowed: min_clearance, or the distance
                               // at q = 0 less kHomeTolerance when the pair starts closer
  double home_distance = 0.0;  // [m] at q = 0
  // [m/rad] per joint, at any pose: how fast a point of either side moves
  // relative to the other per unit rate of the joint (0 for joints on
  // neither chain or on both, which move the two rigidly together). So the
  // distance at q' is at least the distance at q less Σ_j reach_j |q'_j − q_j|.
  std::vector<double> reach;
  std::string Name(const RobotModel& model) const;  // "link2–link5", "link4–ground", "link4–table"
  // The other side's name: a link's (a ground link's), "ground" (the floor) or the obstacle's.
  std::string Other(const RobotModel& model) const;
};

struct Clearance {
  double distance = 0.0;                             // [m]; < 0 when the shapes overlap
  Eigen::Vector3d p_a_W = Eigen::Vector3d::Zero();   // closest point on link a
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();    // unit, from b towards a: d grows along it
};

class ClearanceModel {
 public:
  // [m] a pair held at its distance at q = 0 may come this much closer: GJK's
  // accuracy, so that a pair whose distance no joint changes meets its minimum.
  static constexpr double kHomeTolerance = 1e-6;
  // [m] the same for a pair whose shapes touch or overlap at q = 0: their
  // distance is a penetration depth by EPA, whose stopping tolerance is 1e-4
  // (Bullet's EPA_ACCURACY; a face resting on a face measures alike to 1e-12 m
  // at every turn about the vertical, LinkClearanceTest).
  static constexpr double kContactTolerance = 1e-4;

  // The links against each other, the scene's floor (when scene.floor) and
  // its obstacles, the base at `base` in the world. Throws
  // std::invalid_argument if min_clearance < 0 (or is not finite), or naming
  // the field of an invalid scene or base pose (Cell/BasePose::IsValid).
  ClearanceModel(const RobotModel& model, double min_clearance, const Cell& scene = Cell(),
                 const BasePose& base = BasePose());
  ~ClearanceModel();
  ClearanceModel(ClearanceModel&&) noexcept;
  ClearanceModel& operator=(ClearanceModel&&) noexcept;

  double min_clearance() const { return min_clearance_; }
  const std::vector<ClearancePair>& pairs() const { return pairs_; }
  // The pairs not checked, one line each: "a–b: <reason>".
  const std::vector<std::string>& excluded() const { return excluded_; }
  // The number of pairs whose minimum is their distance at q = 0 (< min_clearance).
  int n_held_at_home() const;

  // The clearance of every pair at the link poses in k (one entry per pair).
  // With at_least (one value per pair), a pair whose shapes' bounding
  // capsules (LowerBound) are at least that far apart gets that lower bound
  // instead (no GJK; its points and normal are unset): enough to track a
  // minimum over instants.
  void Compute(const KinematicsData<double>& k, std::vector<Clearance>* out,
               const std::vector<double>* at_least = nullptr) const;

  // The clearance of pair i alone (pairs()[i]) at the link poses in k; with
  // a finite at_least, pruned as Compute does.
  Clearance ComputePair(const KinematicsData<double>& k, int i,
                        double at_least = std::numeric_limits<double>::infinity()) const;

  // A lower bound of pair i's distance at the link poses in k, without GJK:
  // the distance between capsules holding the shapes (a segment along a
  // box's longest side, a cylinder's axis or a mesh's principal axis, with
  // the radius reaching every point of the shape as GJK sees it). For the
  // floor, the capsule's lowest point.
  double LowerBound(const KinematicsData<double>& k, int i) const;

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
