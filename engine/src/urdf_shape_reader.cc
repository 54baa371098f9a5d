#include "urdf_shape_reader.h"

#include <utility>

#include "mesh_uri.h"
#include "urdf_messages.h"

namespace idbench::internal {

UrdfShapeReader::UrdfShapeReader(std::filesystem::path base_directory, std::vector<std::string>* warnings)
    : base_directory_(std::move(base_directory)), warnings_(warnings) {}

std::vector<urdf::VisualSharedPtr> UrdfShapeReader::Visuals(const urdf::Link& link) {
  if (!link.visual_array.empty()) return link.visual_array;
  if (link.visual != nullptr) return {link.visual};
  return {};
}

std::vector<urdf::CollisionSharedPtr> UrdfShapeReader::Collisions(const urdf::Link& link) {
  if (!link.collision_array.empty()) return link.collision_array;
  if (link.collision != nullptr) return {link.collision};
  return {};
}

// A <visual> or <collision> geometry placed at X_BG; nullopt (with a
// warning) for a mesh that cannot be found or read.
std::optional<Shape> UrdfShapeReader::ReadShape(const urdf::Geometry& geometry, const Eigen::Isometry3d& X_BG,
                                                const std::string& where) {
  Shape shape;
  shape.X_BG = X_BG;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
      shape.kind = Shape::Kind::kBox;
      shape.size = Eigen::Vector3d(dim.x, dim.y, dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      shape.kind = Shape::Kind::kCylinder;
      shape.size = Eigen::Vector3d(cylinder.radius, cylinder.radius, cylinder.length);
      break;
    }
    case urdf::Geometry::SPHERE: {
      const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
      shape.kind = Shape::Kind::kSphere;
      shape.size = Eigen::Vector3d::Constant(radius);
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      shape.kind = Shape::Kind::kMesh;
      shape.size = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      shape.mesh_uri = mesh.filename;
      shape.mesh = Mesh(mesh.filename, shape.size, where, &shape.mesh_uri);
      if (shape.mesh == nullptr) return std::nullopt;
      break;
    }
    default:
      return std::nullopt;
  }
  return shape;
}

// The mesh a <mesh filename> names, read once per file and scale; null with
// a warning when it cannot be found or read (the link then lacks that shape).
// A relative path in *uri is made absolute (so that a URDF written
// elsewhere still finds it).
std::shared_ptr<const TriangleMesh> UrdfShapeReader::Mesh(const std::string& uri, const Eigen::Vector3d& scale,
                                                          const std::string& where, std::string* written_uri) {
  std::vector<std::string> looked;
  const std::optional<std::filesystem::path> path = ResolveMeshUri(uri, base_directory_, &looked);
  if (!path) {
    std::string places;
    for (const std::string& p : looked) places += (places.empty() ? "" : ", ") + p;
    warnings_->push_back(where + "mesh " + Quote(uri) + " not found (looked in " + places +
                        "; set ROS_PACKAGE_PATH for package:// names); shape skipped");
    return nullptr;
  }
  if (uri.find("://") == std::string::npos && std::filesystem::path(uri).is_relative()) *written_uri = path->string();
  const std::string key = path->string() + " " + std::to_string(scale.x()) + " " + std::to_string(scale.y()) +
                          " " + std::to_string(scale.z());
  // A file read (or refused, with its one warning) once: a mesh used by a
  // <visual> and a <collision> is not read or reported twice.
  if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
  std::shared_ptr<const TriangleMesh>& mesh = meshes_[key];
  try {
    mesh = std::make_shared<const TriangleMesh>(LoadTriangleMesh(path->string(), scale));
  } catch (const std::exception& e) {
    warnings_->push_back(where + e.what() + "; the shapes using it are skipped");
  }
  return mesh;
}

}  // namespace idbench::internal
