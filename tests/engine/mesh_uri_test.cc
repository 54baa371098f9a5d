#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/test_meshes.h"
#include "engine/urdf_test_util.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Meshes ----

namespace mesh_test {

std::string MeshLink(const std::string& name, const std::string& filename, const std::string& scale) {
  return "<link name=\"" + name + "\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" "
         "iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial><visual><origin xyz=\"0 0 0.2\"/><geometry><mesh "
         "filename=\"" + filename + "\" scale=\"" + scale + "\"/></geometry></visual></link>";
}
std::string Joint(const std::string& parent, const std::string& child) {
  return "<joint name=\"" + child + "_joint\" type=\"continuous\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"0 0 0.5\"/><axis xyz=\"0 1 0\"/></joint>";
}

}  // namespace mesh_test

// A robot package laid out as ROS does (cubepkg/urdf/r.urdf, cubepkg/meshes/):
// package:// names resolve to the directory of that name above the URDF,
// relative names against the URDF's directory (written back absolute), a
// missing file is a warning naming the link and the file; the writer keeps
// the meshes, and the written URDF reads back the same shapes.
TEST(UrdfTest, MeshesResolveLikeRosPackagesAndRoundTrip) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("idbench_urdf_mesh_" + std::to_string(::getpid()));
  fs::create_directories(root / "cubepkg" / "urdf");
  fs::create_directories(root / "cubepkg" / "meshes");
  idbench::testing::WriteAsciiStl(idbench::testing::BoxMesh(Eigen::Vector3d::Ones()),
                                  (root / "cubepkg" / "meshes" / "box.stl").string());
  using mesh_test::Joint, mesh_test::MeshLink;
  const std::string xml = "<robot name=\"meshy\"><link name=\"base\"/>" +
                          MeshLink("L1", "package://cubepkg/meshes/box.stl", "0.1 0.2 0.3") + Joint("base", "L1") +
                          MeshLink("L2", "../meshes/box.stl", "1 1 1") + Joint("L1", "L2") +
                          MeshLink("L3", "package://cubepkg/meshes/missing.stl", "1 1 1") + Joint("L2", "L3") +
                          "</robot>";
  const fs::path urdf = root / "cubepkg" / "urdf" / "r.urdf";
  std::ofstream(urdf) << xml;
  UrdfLoadResult loaded = LoadUrdfFile(urdf.string());
  loaded.warnings = WithoutGeometryWarnings(loaded.warnings);  // the boxes are placed freely
  const RobotModel& m = loaded.model;
  ASSERT_EQ(m.link(0).shapes.size(), 1u);
  const Shape& s1 = m.link(0).shapes[0];
  ASSERT_EQ(s1.kind, Shape::Kind::kMesh);
  ExpectNear(s1.mesh->hi_G, Eigen::Vector3d(0.05, 0.1, 0.15), 1e-6, "scaled box");
  ExpectNear(s1.X_BG.translation(), Eigen::Vector3d(0, 0, 0.2), 0.0, "visual origin");
  EXPECT_EQ(s1.mesh_uri, "package://cubepkg/meshes/box.stl");
  ASSERT_EQ(m.link(1).shapes.size(), 1u);
  EXPECT_EQ(fs::path(m.link(1).shapes[0].mesh_uri), fs::absolute(root / "cubepkg" / "meshes" / "box.stl"));
  EXPECT_TRUE(m.link(2).shapes.empty());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("'L3'"), std::string::npos) << loaded.warnings[0];
  EXPECT_NE(loaded.warnings[0].find("missing.stl"), std::string::npos) << loaded.warnings[0];

  const UrdfLoadResult again = LoadUrdfString(WriteUrdf(m), "written", urdf.parent_path().string());
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(again.model.link(i).shapes.size(), 1u);
    const Shape& a = again.model.link(i).shapes[0];
    EXPECT_EQ(a.mesh_uri, m.link(i).shapes[0].mesh_uri);
    ExpectNear(a.mesh->hi_G, m.link(i).shapes[0].mesh->hi_G, 1e-12, "mesh after the round trip");
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace idbench
