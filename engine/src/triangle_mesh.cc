#include "idbench/engine/triangle_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace idbench {
namespace {

// Appends node's meshes, placed by `transform` (the node's, accumulated from
// the root), and its children's.
void AddNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& transform, TriangleMesh* out) {
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int first = static_cast<int>(out->vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out->vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by the triangulation
      out->triangles.emplace_back(first + static_cast<int>(face.mIndices[0]), first + static_cast<int>(face.mIndices[1]),
                                  first + static_cast<int>(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    AddNode(scene, *node.mChildren[c], transform * node.mChildren[c]->mTransformation, out);
  }
}

}  // namespace

TriangleMesh LoadTriangleMesh(const std::string& path, const Eigen::Vector3d& scale) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::runtime_error("mesh '" + path + "': " + importer.GetErrorString());
  }
  TriangleMesh mesh;
  // COLLADA: assimp rotates a Z_UP file into Y_UP at the root; ROS tools
  // (rviz, geometric_shapes) drop that rotation and keep the root's scale
  // (the file's <unit>) and offset, and so do we.
  aiMatrix4x4 root = scene->mRootNode->mTransformation;
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".dae" || extension == ".zae") {
    aiVector3D scaling, position;
    aiQuaternion rotation;
    root.Decompose(scaling, rotation, position);
    root = aiMatrix4x4(scaling, aiQuaternion(), position);
  }
  AddNode(*scene, *scene->mRootNode, root, &mesh);
  if (mesh.triangles.empty()) throw std::runtime_error("mesh '" + path + "': no triangles");
  mesh.lo_G = Eigen::Vector3d::Constant(INFINITY);
  mesh.hi_G = -mesh.lo_G;
  for (Eigen::Vector3d& v : mesh.vertices) {
    v = v.cwiseProduct(scale);
    mesh.lo_G = mesh.lo_G.cwiseMin(v), mesh.hi_G = mesh.hi_G.cwiseMax(v);
  }
  // A mirroring scale turns the triangles inside out.
  if (scale.prod() < 0.0) {
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  return mesh;
}

}  // namespace idbench
