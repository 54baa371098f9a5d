#include "idbench/engine/triangle_mesh.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "engine/test_meshes.h"
#include "engine/test_util.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class TriangleMeshTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_mesh_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// An STL box read back: 8 joined vertices, 12 triangles, the scaled bounding
// box, and the enclosed volume (divergence theorem) equal to the product of
// the scaled edges: the triangles stay outward, also under a mirroring scale.
TEST_F(TriangleMeshTest, StlBoxReadsBackScaledAndOutward) {
  const fs::path path = dir_ / "box.stl";
  testing::WriteAsciiStl(testing::BoxMesh(Eigen::Vector3d(1.0, 2.0, 0.5)), path.string());
  ASSERT_NEAR(testing::MeshVolume(testing::BoxMesh(Eigen::Vector3d(1.0, 2.0, 0.5))), 1.0, 1e-12);
  const TriangleMesh mesh = LoadTriangleMesh(path.string(), Eigen::Vector3d(2.0, 3.0, 4.0));
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_LT(testing::RelativeError(mesh.lo_G, Eigen::Vector3d(-1.0, -3.0, -1.0)), 1e-6);
  EXPECT_LT(testing::RelativeError(mesh.hi_G, Eigen::Vector3d(1.0, 3.0, 1.0)), 1e-6);
  EXPECT_NEAR(testing::MeshVolume(mesh), 24.0, 1e-5);
  const TriangleMesh mirrored = LoadTriangleMesh(path.string(), Eigen::Vector3d(-1.0, 1.0, 1.0));
  EXPECT_NEAR(testing::MeshVolume(mirrored), 1.0, 1e-6);
}

TEST_F(TriangleMeshTest, UnreadableFilesNameThePath) {
  const std::string missing = (dir_ / "missing.stl").string();
  try {
    LoadTriangleMesh(missing);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const fs::path garbage = dir_ / "garbage.stl";
  std::ofstream(garbage) << "solid x\n facet nonsense\nendsolid\n";
  EXPECT_THROW(LoadTriangleMesh(garbage.string()), std::runtime_error);
}

}  // namespace
}  // namespace idbench
