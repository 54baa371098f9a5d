// Meshes for tests: a box as triangles, written as ASCII STL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fstream>
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
