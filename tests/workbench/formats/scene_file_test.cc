#include "idbench/workbench/formats/scene_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "engine/test_util.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

using testing::ExpectInvalid;

// The issue's example (a mesh from the test robot's meshes): every type,
// its size in Shape's convention, the pose as URDF's <origin>.
TEST(SceneFileTest, ReadsEveryObstacleTypeWithItsWorldPose) {
  const Cell cell = ParseSceneJson(R"({"floor": false,
    "obstacles": [{"type": "box", "name": "table", "size": [2.0, 2.0, 0.05], "pose": [0, 0, -0.026, 0, 0, 0]},
                  {"type": "cylinder", "radius": 0.1, "length": 1.0, "pose": [0.5, 0.2, 0.5, 0.3, 0, 1.2]},
                  {"type": "sphere", "radius": 0.2, "pose": [-1, 0, 1, 0, 0, 0]},
                  {"type": "mesh", "path": "meshes/wrist_3_link.stl", "scale": [2, 2, 2], "pose": [0, 1, 0, 0, 0, 0]}]})",
                                   "scene.json", IDBENCH_SOURCE_DIR "/tests/data/ur10e_like");
  EXPECT_FALSE(cell.floor);
  ASSERT_EQ(cell.obstacles.size(), 4u);
  EXPECT_EQ(cell.ObstacleName(0), "table");
  EXPECT_EQ(cell.ObstacleName(1), "obstacle 1");
  EXPECT_EQ(cell.obstacles[0].shape.kind, Shape::Kind::kBox);
  EXPECT_EQ(cell.obstacles[0].shape.size, Eigen::Vector3d(2.0, 2.0, 0.05));
  EXPECT_EQ(cell.obstacles[1].shape.size, Eigen::Vector3d(0.1, 0.1, 1.0));
  EXPECT_TRUE(cell.obstacles[1].X_WO.linear().isApprox(RotationFromRpy(Eigen::Vector3d(0.3, 0, 1.2)), 1e-15));
  EXPECT_EQ(cell.obstacles[1].X_WO.translation(), Eigen::Vector3d(0.5, 0.2, 0.5));
  EXPECT_EQ(cell.obstacles[2].shape.size, Eigen::Vector3d::Constant(0.2));
  ASSERT_EQ(cell.obstacles[3].shape.kind, Shape::Kind::kMesh);
  ASSERT_TRUE(cell.obstacles[3].shape.mesh);
  // Scaled by 2: the same mesh read at scale 1 is half as far out.
  const TriangleMesh unit = LoadTriangleMesh(IDBENCH_SOURCE_DIR "/tests/data/ur10e_like/meshes/wrist_3_link.stl");
  ASSERT_EQ(unit.vertices.size(), cell.obstacles[3].shape.mesh->vertices.size());
  EXPECT_TRUE(cell.obstacles[3].shape.mesh->vertices[0].isApprox(2.0 * unit.vertices[0], 1e-12));
  // Both keys optional: the floor alone.
  const Cell empty = ParseSceneJson("{}", "s.json", ".");
  EXPECT_TRUE(empty.floor);
  EXPECT_TRUE(empty.obstacles.empty());
}

// Each refusal names the file and the field, as "scene.json: .obstacles[2].radius: …".
TEST(SceneFileTest, RefusalsNameTheFileAndTheField) {
  const auto refusal = [](const std::string& text) {
    return ExpectInvalid([&] { ParseSceneJson(text, "scene.json", "."); });
  };
  const std::string sphere = R"({"type": "sphere", "radius": 0.1, "pose": [0, 0, 0, 0, 0, 0]})";
  EXPECT_EQ(refusal(R"({"obstacles": [)" + sphere + "," + sphere +
                    R"(, {"type": "sphere", "radius": -1, "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[2].radius: expected a number > 0 [m], got -1", 0),
            0u);
  EXPECT_EQ(refusal(R"({"flor": false})").rfind("scene.json: .flor: unknown key (floor, obstacles)", 0), 0u);
  EXPECT_EQ(refusal(R"({"floor": 0})").rfind("scene.json: .floor: expected true or false", 0), 0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "box", "size": [1, 1, 1], "radius": 1, "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].radius: unknown key for this type (name, pose, size, type)", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "box", "size": [1, 1, 1]}]})")
                .rfind("scene.json: .obstacles[0].pose: missing", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "box", "size": [1, 0, 1], "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].size[1]: expected a finite number > 0", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "cone", "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].type: expected \"box\", \"cylinder\", \"sphere\" or \"mesh\"", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "sphere", "radius": 0.1, "pose": [0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].pose: expected 6 numbers", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "mesh", "path": "missing.stl", "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].path: ", 0),
            0u);
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "box", "size": [200, 1, 1], "pose": [0, 0, 0, 0, 0, 0]}]})")
                .rfind("scene.json: .obstacles[0].size: expected finite sizes in (0, 100] m", 0),
            0u);
  EXPECT_EQ(refusal("[1, 2]").rfind("scene.json: expected an object", 0), 0u);
  EXPECT_EQ(refusal("{").rfind("scene.json: not valid JSON: ", 0), 0u);
  // Issue 35 item 9: a key given twice (1c4dd0f kept the last).
  EXPECT_EQ(refusal(R"({"obstacles": [{"type": "sphere", "radius": 0.1, "radius": 0.5, "pose": [0, 0, 0, 0, 0, 0]}]})"),
            "scene.json: .obstacles[0].radius: key repeated in one object (each key may be given once)");
  // The bound on the count: Cell::kMaxObstacles.
  std::string many = R"({"obstacles": [)";
  for (int i = 0; i <= Cell::kMaxObstacles; ++i) many += (i ? "," : "") + sphere;
  EXPECT_EQ(refusal(many + "]}").rfind("scene.json: .obstacles: at most 64 obstacles, got 65", 0), 0u);
}

}  // namespace
}  // namespace idbench
