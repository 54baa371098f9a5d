#include "idbench/engine/triangle_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "idbench/engine/input_file.h"

namespace idbench {
namespace {

// Appends the meshes of `root` and of every node below it, each placed by its
// node's transform accumulated from `root` (whose own is `transform`). Walked
// with a stack of its own: a deeply nested file cannot overflow the call stack.
void AddNodes(const aiScene& scene, const aiNode& root, const aiMatrix4x4& transform, TriangleMesh* out) {
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{&root, transform}};
  while (!stack.empty()) {
    const auto [node, X] = stack.back();
    stack.pop_back();
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[m]];
      if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      const int first = static_cast<int>(out->vertices.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D p = X * mesh.mVertices[v];
        out->vertices.emplace_back(p.x, p.y, p.z);
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines left by the triangulation
        out->triangles.emplace_back(first + static_cast<int>(face.mIndices[0]),
                                    first + static_cast<int>(face.mIndices[1]),
                                    first + static_cast<int>(face.mIndices[2]));
      }
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      stack.emplace_back(node->mChildren[c], X * node->mChildren[c]->mTransformation);
    }
  }
}

}  // namespace

TriangleMesh LoadTriangleMesh(const std::string& path, const Eigen::Vector3d& scale) {
  // Only a regular file within the input size limit (assimp reads it whole).
  try {
    CheckInputFile(path);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("mesh ") + e.what());
  }
  Assimp::Importer importer;
  // Read as the file says, check every vertex is finite (joining identical
  // vertices would merge a NaN one away), then triangulate and join.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene != nullptr) {
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene->mMeshes[m];
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& p = mesh.mVertices[v];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
          throw std::runtime_error("mesh '" + path + "': vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                                   " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                                   std::to_string(p.z) + "); correct the file");
        }
      }
    }
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                         aiProcess_SortByPType);
  }
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
  AddNodes(*scene, *scene->mRootNode, root, &mesh);
  if (mesh.triangles.empty()) throw std::runtime_error("mesh '" + path + "': no triangles");
  mesh.lo_G = Eigen::Vector3d::Constant(INFINITY);
  mesh.hi_G = -mesh.lo_G;
  for (Eigen::Vector3d& v : mesh.vertices) {
    v = v.cwiseProduct(scale);
    if (!v.allFinite()) {
      throw std::runtime_error("mesh '" + path + "': a vertex is not finite once placed and scaled (the file's " +
                               "transforms or units overflow); correct the file");
    }
    mesh.lo_G = mesh.lo_G.cwiseMin(v), mesh.hi_G = mesh.hi_G.cwiseMax(v);
  }
  // A mirroring scale turns the triangles inside out.
  if (scale.prod() < 0.0) {
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  return mesh;
}

}  // namespace idbench
