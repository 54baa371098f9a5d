// A triangle mesh attached to a link (a URDF <mesh> visual), read with assimp.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace idbench {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;   // p_GoV_G [m], the file's scale applied (n_vertices)
  std::vector<Eigen::Vector3i> triangles;  // vertex indices, counter-clockwise seen from outside
  Eigen::Vector3d lo_G = Eigen::Vector3d::Zero(), hi_G = Eigen::Vector3d::Zero();  // bounding box in G [m]
};

// Reads every mesh of a file assimp understands (STL, COLLADA .dae, OBJ,
// …), each placed by its node's transform, triangulated, identical vertices
// joined, scaled by `scale` per axis (URDF's scale attribute). COLLADA as in
// ROS (rviz, geometric_shapes): the file's <unit> applies, its <up_axis> does
// not (assimp's rotation to Y_UP at the root is dropped). Throws
// std::runtime_error naming the file and assimp's reason when it cannot be
// read or holds no triangle.
TriangleMesh LoadTriangleMesh(const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace idbench
