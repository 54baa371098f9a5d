// The support mapping of a convex hull by hill climbing on its edges
// (internal to engine/src; link_clearance.cc's mesh hulls for GJK).
//
// The support point of a point set P along d is a p ∈ P of greatest d·p. A
// scan costs |P| dot products per call; GJK asks for one per iteration with
// a direction that changes little from the last. On a convex polytope a
// vertex that no edge leaves upwards (d·neighbour ≤ d·vertex for every
// neighbour) is a maximum of d·p over the whole polytope (the simplex
// method's optimality condition), so climbing the hull's edge graph from any
// vertex, always to the highest neighbour, ends at a support point: exact,
// and from the last support point a few steps of ~6 dot products each.
// Bullet's GJK scans (btConvexHullShape); this climbs instead, as MuJoCo's
// mesh support does on its mesh graph (hand-written: Bullet has no climbing
// support function).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace idbench::internal {

class HullClimb {
 public:
  // The convex hull of `points` (≤ kMaxPoints; its edges by Bullet's
  // btConvexHullComputer). usable() is false when the hull has no edge
  // graph to climb (fewer than 4 points, or a climb
  // that did not reach a scan's value in one of the check directions):
  // callers then scan. Throws std::invalid_argument above kMaxPoints.
  static constexpr int kMaxPoints = 1 << 16;
  explicit HullClimb(const std::vector<Eigen::Vector3d>& points);

  bool usable() const { return usable_; }
  int n_vertices() const { return static_cast<int>(vertices_.size()); }
  // Hull vertex v's point (one of the points given).
  const Eigen::Vector3d& vertex(int v) const { return vertices_[static_cast<size_t>(v)]; }

  // A hull vertex of greatest d·p, climbing from the higher along d of
  // vertex *from (when a valid vertex index: the last call's) and the
  // support vertex of the cube-map cell d falls in (a table of each cell
  // centre's support vertex); *from is set to the vertex reached (the next
  // call's warm start). d need not be unit. Requires usable().
  int Support(const Eigen::Vector3d& d, int* from) const;

 private:
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<int> first_;       // vertex v's neighbours: neighbours_[first_[v] .. first_[v + 1])
  std::vector<int> neighbours_;
  // Directions binned by their dominant axis and sign (6 faces of a cube)
  // and a kCells × kCells grid on each face: the support vertex of each
  // cell's centre direction.
  static constexpr int kCells = 16;
  static int Cell(const Eigen::Vector3d& d);
  std::vector<int> cell_support_;  // 6 · kCells² entries
  bool usable_ = false;
};

}  // namespace idbench::internal
