// Meshes for tests: a box as triangles, written as ASCII STL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <utility>
#include <vector>
#include <string>

#include "idbench/engine/triangle_mesh.h"

namespace idbench::testing {

// A box with these edge lengths, centred at the origin: 8 vertices, 12
// triangles counter-clockwise seen from outside.
inline TriangleMesh BoxMesh(const Eigen::Vector3d& edges) {
  TriangleMesh mesh;
  for (int corner = 0; corner < 8; ++corner) {
    mesh.vertices.emplace_back((corner & 1 ? 0.5 : -0.5) * edges.x(), (corner & 2 ? 0.5 : -0.5) * edges.y(),
                               (corner & 4 ? 0.5 : -0.5) * edges.z());
  }
  // Faces as corner quads (outward, counter-clockwise), two triangles each.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.emplace_back(q[0], q[1], q[2]);
    mesh.triangles.emplace_back(q[0], q[2], q[3]);
  }
  mesh.lo_G = -0.5 * edges, mesh.hi_G = 0.5 * edges;
  return mesh;
}

// A sphere of this radius as an icosahedron subdivided `levels` times, every
// vertex on the sphere (levels = 3: 642 vertices, 1280 triangles).
inline TriangleMesh IcosphereMesh(double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Eigen::Vector3d& p : v) p.normalize();
  std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (const auto it = middle.find(key); it != middle.end()) return it->second;
      v.push_back((v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)]).normalized());
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> finer;
    for (const Eigen::Vector3i& tri : f) {
      const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      finer.insert(finer.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(finer);
  }
  TriangleMesh mesh;
  for (const Eigen::Vector3d& p : v) mesh.vertices.push_back(radius * p);
  mesh.triangles = std::move(f);
  mesh.lo_G = Eigen::Vector3d::Constant(-radius), mesh.hi_G = Eigen::Vector3d::Constant(radius);
  return mesh;
}

// Σ a·(b × c)/6 over the triangles: the enclosed volume when they are closed
// and outward (divergence theorem).
inline double MeshVolume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return volume;
}

inline void WriteAsciiStl(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out << "solid test\n";
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = mesh.vertices[t[k]];
      out << "   vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    }
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid test\n";
}

}  // namespace idbench::testing
