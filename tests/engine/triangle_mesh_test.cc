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

// COLLADA as ROS reads it: <unit meter="0.01"> scales (a box of 100 × 200 ×
// 50 units is 1 × 2 × 0.5 m) and <up_axis>Z_UP</up_axis> does not rotate it
// (z keeps the 0.5 m edge).
TEST_F(TriangleMeshTest, ColladaKeepsItsUnitAndIgnoresItsUpAxis) {
  const TriangleMesh box = testing::BoxMesh(Eigen::Vector3d(100.0, 200.0, 50.0));
  std::string positions, indices;
  for (const Eigen::Vector3d& v : box.vertices) {
    positions += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + " ";
  }
  for (const Eigen::Vector3i& t : box.triangles) {
    indices += std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " ";
  }
  const fs::path path = dir_ / "box.dae";
  std::ofstream(path) << R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="24">)" << positions << R"(</float_array>
      <technique_common><accessor source="#pa" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="12"><input semantic="VERTEX" source="#v" offset="0"/><p>)" << indices << R"(</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
  const TriangleMesh mesh = LoadTriangleMesh(path.string());
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_LT(testing::RelativeError(mesh.hi_G, Eigen::Vector3d(0.5, 1.0, 0.25)), 1e-6);
  EXPECT_LT(testing::RelativeError(mesh.lo_G, Eigen::Vector3d(-0.5, -1.0, -0.25)), 1e-6);
  EXPECT_NEAR(testing::MeshVolume(mesh), 1.0, 1e-6);
}

}  // namespace
}  // namespace idbench
