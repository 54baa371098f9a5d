#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "engine/urdf_test_util.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Meshes ----

// A missing mesh is named whole in the warning, however long its path (a
// 65-byte package:// URI of the KUKA LWR4+ was cut to 64 bytes), while a
// name beyond any path's length is still cut.
TEST(UrdfTest, MissingMeshIsNamedWhole) {
  const std::string uri = "package://some_vendor_description/meshes/visual/" + std::string(200, 'x') + ".stl";
  const std::string mesh = "<geometry><mesh filename=\"" + uri + "\"/></geometry>";
  const UrdfLoadResult loaded = LoadUrdfString(
      Robot(BareLink("base") + "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" "
            "ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial><visual>" + mesh + "</visual></link>\n" +
            Joint("j1", "revolute", "base", "a")));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("'" + uri + "' not found"), std::string::npos) << loaded.warnings[0];
}

// <collision> geometry is kept apart from <visual>: drawn shapes from the
// visuals, clearance from the collisions, both written back.
TEST(UrdfTest, CollisionGeometryIsKeptApartFromVisuals) {
  const std::string xml =
      "<robot name=\"c\"><link name=\"base\"/><link name=\"L1\"><inertial><mass value=\"1\"/><inertia "
      "ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>"
      "<visual><geometry><sphere radius=\"0.3\"/></geometry></visual>"
      "<collision><origin xyz=\"0 0 0.1\"/><geometry><box size=\"0.1 0.2 0.3\"/></geometry></collision>"
      "<collision><geometry><cylinder radius=\"0.05\" length=\"0.4\"/></geometry></collision></link>"
      "<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"L1\"/>"
      "<axis xyz=\"0 0 1\"/></joint></robot>";
  const RobotModel m = LoadUrdfString(xml).model;
  const Link& l = m.link(0);
  ASSERT_EQ(l.shapes.size(), 1u);
  EXPECT_EQ(l.shapes[0].kind, Shape::Kind::kSphere);
  ASSERT_EQ(l.collision_shapes.size(), 2u);
  EXPECT_EQ(l.collision_shapes[0].kind, Shape::Kind::kBox);
  ExpectNear(l.collision_shapes[0].size, Eigen::Vector3d(0.1, 0.2, 0.3), 0.0, "box");
  ExpectNear(l.collision_shapes[0].X_BG.translation(), Eigen::Vector3d(0, 0, 0.1), 0.0, "box origin");
  EXPECT_EQ(l.collision_shapes[1].kind, Shape::Kind::kCylinder);
  EXPECT_EQ(&l.CollisionShapes(), &l.collision_shapes);
  const RobotModel again = LoadUrdfString(WriteUrdf(m)).model;
  ASSERT_EQ(again.link(0).shapes.size(), 1u);
  ASSERT_EQ(again.link(0).collision_shapes.size(), 2u);
  ExpectNear(again.link(0).collision_shapes[1].size, l.collision_shapes[1].size, 0.0, "cylinder after the round trip");
}

// A mesh that is a FIFO, a device or a directory is named as such (it was
// "not found"), and a bad mesh used by a visual and a collision warns once.
TEST(UrdfTest, BadMeshesWarnOnceSayingWhatIsWrong) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("idbench_urdf_badmesh_" + std::to_string(::getpid()));
  fs::create_directories(root / "dir.stl");
  ASSERT_EQ(::mkfifo((root / "fifo.stl").c_str(), 0600), 0);
  {
    // Binary STL: one triangle, a NaN in its second vertex.
    std::ofstream stl(root / "nan.stl", std::ios::binary);
    const std::string header(80, ' ');
    const std::uint32_t count = 1;
    const float triangle[12] = {0, 0, 1, 0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1, 0};
    const std::uint16_t attribute = 0;
    stl.write(header.data(), 80).write(reinterpret_cast<const char*>(&count), 4);
    stl.write(reinterpret_cast<const char*>(triangle), sizeof(triangle)).write(reinterpret_cast<const char*>(&attribute), 2);
  }
  for (const auto& [file, why] : std::vector<std::pair<std::string, std::string>>{
           {(root / "fifo.stl").string(), "is a FIFO"},
           {"/dev/zero", "is a character device"},
           {(root / "dir.stl").string(), "is a directory"},
           {(root / "nan.stl").string(), "is not finite"}}) {
    const std::string mesh = "<geometry><mesh filename=\"" + file + "\"/></geometry>";
    const std::string xml = Robot(BareLink("base") +
                                  "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" "
                                  "ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial><visual>" + mesh +
                                  "</visual><collision>" + mesh + "</collision></link>\n" +
                                  Joint("j1", "revolute", "base", "a"));
    const UrdfLoadResult loaded = LoadUrdfString(xml);
    ASSERT_EQ(loaded.warnings.size(), 1u) << file;
    EXPECT_NE(loaded.warnings[0].find(why), std::string::npos) << loaded.warnings[0];
    EXPECT_EQ(loaded.warnings[0].find("not found"), std::string::npos) << loaded.warnings[0];
    EXPECT_TRUE(loaded.model.link(0).shapes.empty() && loaded.model.link(0).collision_shapes.empty());
  }
  // A mesh over the input limit (a sparse file: nothing on disk) is not read:
  // a 2 GB one took 2.2 GB of memory.
  const fs::path big = root / "big.stl";
  std::ofstream(big).close();
  fs::resize_file(big, 3 * 1024 * 1024);
  ::setenv("IDBENCH_MAX_INPUT_MB", "2", 1);
  const UrdfLoadResult loaded = LoadUrdfString(
      Robot(BareLink("base") + "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" "
            "iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial><visual><geometry><mesh filename=\"" + big.string() +
            "\"/></geometry></visual></link>\n" + Joint("j1", "revolute", "base", "a")));
  ::unsetenv("IDBENCH_MAX_INPUT_MB");
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("mesh " + big.string() + ": the file is 3 MB, larger than the limit for input "
                                    "files, 2 MB (IDBENCH_MAX_INPUT_MB sets it"),
            std::string::npos) << loaded.warnings[0];
  fs::remove_all(root);
}

}  // namespace
}  // namespace idbench
