// The shapes of a URDF link's <visual> and <collision> elements (internal to
// engine/src): box, cylinder, sphere and mesh, each mesh file found by
// ResolveMeshUri (mesh_uri.h) and read once per file and scale.
#pragma once

#include <urdf_model/link.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench::internal {

class UrdfShapeReader {
 public:
  // Relative mesh paths start at base_directory; a mesh that cannot be found
  // or read is reported in *warnings (which must outlive the reader).
  UrdfShapeReader(std::filesystem::path base_directory, std::vector<std::string>* warnings);

  // A link's <visual> (<collision>) elements, also when urdfdom keeps only one.
  static std::vector<urdf::VisualSharedPtr> Visuals(const urdf::Link& link);
  static std::vector<urdf::CollisionSharedPtr> Collisions(const urdf::Link& link);

  // A <visual> or <collision> geometry placed at X_BG; nullopt (with a
  // warning starting with `where`) for a mesh that cannot be found or read.
  std::optional<Shape> ReadShape(const urdf::Geometry& geometry, const Eigen::Isometry3d& X_BG,
                                 const std::string& where);

 private:
  std::shared_ptr<const TriangleMesh> Mesh(const std::string& uri, const Eigen::Vector3d& scale,
                                           const std::string& where, std::string* written_uri);

  std::filesystem::path base_directory_;  // relative mesh paths start here
  std::vector<std::string>* warnings_;
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes_;  // by path and scale; null: refused
};

}  // namespace idbench::internal
