#include "hull_climb.h"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace idbench::internal {

HullClimb::HullClimb(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() > static_cast<size_t>(kMaxPoints)) {
    throw std::invalid_argument("HullClimb: " + std::to_string(points.size()) + " points, at most " +
                                std::to_string(kMaxPoints));
  }
  if (points.size() < 4) return;
  // The hull's vertices (mapped back to the points given, so that a support
  // point is one of them bit for bit) and its edges, each once per direction.
  btConvexHullComputer hull;
  hull.compute(points[0].data(), static_cast<int>(sizeof(Eigen::Vector3d)), static_cast<int>(points.size()), 0.0,
               0.0);
  const int n = hull.vertices.size();
  if (n < 4 || hull.original_vertex_index.size() != n) return;
  vertices_.reserve(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) vertices_.push_back(points[static_cast<size_t>(hull.original_vertex_index[v])]);
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(n));
  for (int e = 0; e < hull.edges.size(); ++e) {
    const btConvexHullComputer::Edge& edge = hull.edges[e];
    adjacent[static_cast<size_t>(edge.getSourceVertex())].push_back(edge.getTargetVertex());
  }
  first_.assign(1, 0);
  for (const std::vector<int>& a : adjacent) {
    if (a.empty()) return;  // a vertex without edges: no graph to climb
    neighbours_.insert(neighbours_.end(), a.begin(), a.end());
    first_.push_back(static_cast<int>(neighbours_.size()));
  }
  // The cube map of cold starts: each cell centre's support vertex, by a scan.
  cell_support_.assign(6 * kCells * kCells, 0);
  for (int face = 0; face < 6; ++face) {
    for (int i = 0; i < kCells; ++i) {
      for (int j = 0; j < kCells; ++j) {
        const int axis = face / 2;
        Eigen::Vector3d d;
        d[axis] = face % 2 == 0 ? -1.0 : 1.0;
        d[(axis + 1) % 3] = 2.0 * (i + 0.5) / kCells - 1.0;
        d[(axis + 2) % 3] = 2.0 * (j + 0.5) / kCells - 1.0;
        int best = 0;
        for (int v = 1; v < n; ++v) {
          if (d.dot(vertices_[static_cast<size_t>(v)]) > d.dot(vertices_[static_cast<size_t>(best)])) best = v;
        }
        cell_support_[static_cast<size_t>(Cell(d))] = best;
      }
    }
  }
  // The climb is exact on a polytope's edge graph; a hull Bullet built
  // otherwise (rounding in its integer arithmetic, a point left out) would
  // show here: the climb from a cold and a warm start against a scan of the
  // points given, in 512 directions of a Fibonacci sphere.
  usable_ = true;
  constexpr int kCheckDirections = 512;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  int warm = -1;
  for (int k = 0; k < kCheckDirections && usable_; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / kCheckDirections, r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d d(r * std::cos(golden * k), r * std::sin(golden * k), z);
    int cold = -1;
    double best = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points) best = std::max(best, d.dot(p));
    usable_ = d.dot(vertex(Support(d, &cold))) == best && d.dot(vertex(Support(d, &warm))) == best;
  }
}

int HullClimb::Cell(const Eigen::Vector3d& d) {
  int axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  const double scale = std::abs(d[axis]);
  if (!(scale > 0.0) || !d.allFinite()) return 0;  // d = 0 (or not finite): any cell
  auto bin = [&](double x) { return std::clamp(static_cast<int>((x / scale + 1.0) * 0.5 * kCells), 0, kCells - 1); };
  const int face = 2 * axis + (d[axis] > 0.0 ? 1 : 0);
  return (face * kCells + bin(d[(axis + 1) % 3])) * kCells + bin(d[(axis + 2) % 3]);
}

int HullClimb::Support(const Eigen::Vector3d& d, int* from) const {
  int v = cell_support_[static_cast<size_t>(Cell(d))];
  double v_dot = d.dot(vertices_[static_cast<size_t>(v)]);
  if (*from >= 0 && *from < n_vertices()) {
    const double from_dot = d.dot(vertices_[static_cast<size_t>(*from)]);
    if (from_dot > v_dot) v_dot = from_dot, v = *from;
  }
  // Steepest ascent: to the highest neighbour while one is strictly higher
  // (the values rise strictly, so no vertex is visited twice: at most
  // n_vertices() steps).
  for (;;) {
    int next = v;
    for (int i = first_[static_cast<size_t>(v)]; i < first_[static_cast<size_t>(v) + 1]; ++i) {
      const int u = neighbours_[static_cast<size_t>(i)];
      const double dot = d.dot(vertices_[static_cast<size_t>(u)]);
      if (dot > v_dot) v_dot = dot, next = u;
    }
    if (next == v) break;
    v = next;
  }
  *from = v;
  return v;
}

}  // namespace idbench::internal
