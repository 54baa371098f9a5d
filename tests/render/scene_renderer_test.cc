#include "idbench/render/scene_renderer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "idbench/render/osmesa_context.h"
#include "engine/test_meshes.h"
#include "engine/test_util.h"
#include "render/image_test_util.h"

namespace idbench {
namespace {

using testing::IsRobotPixel;

class SceneRendererTest : public ::testing::Test {
 protected:
  OsMesaContext context_;
  SceneRenderer renderer_{OsMesaContext::loader(), 4};
};

// A sphere seen straight on: its image is where and as large as the pinhole
// model says, computed here by hand (camera along +y, no library matrices).
TEST_F(SceneRendererTest, SphereLandsWhereThePinholeModelPutsIt) {
  constexpr int kWidth = 320, kHeight = 240;
  constexpr double kRadius = 0.5, kDistance = 10.0, kFovY = 0.5;
  const Eigen::Vector3d p_WCenter_W(0.8, 0.0, 1.4);
  Camera camera;
  camera.p_WEye_W = Eigen::Vector3d(0, -kDistance, 1.0);
  camera.p_WTarget_W = Eigen::Vector3d(0, 0, 1.0);
  camera.fov_y = kFovY;
  camera.near = 1.0, camera.far = 50.0;
  Scene scene;
  ScenePrimitive sphere;
  sphere.kind = Shape::Kind::kSphere;
  sphere.size = Eigen::Vector3d::Constant(kRadius);
  sphere.X_WG.translation() = p_WCenter_W;
  sphere.color = Eigen::Vector3f(1.0f, 0.0f, 0.0f);
  scene.primitives.push_back(sphere);
  const Floor out_of_sight{.z = -1000.0, .center_W = Eigen::Vector2d::Zero(), .radius = 1.0};
  const Image image = renderer_.Render(scene, out_of_sight, camera, kWidth, kHeight);
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);

  // Pinhole: camera right = +x, up = +z, depth along +y.
  const double f_px = 0.5 * kHeight / std::tan(kFovY / 2.0);
  const double u = 0.5 * kWidth + f_px * p_WCenter_W.x() / kDistance;          // pixel centres at +0.5
  const double v = 0.5 * kHeight - f_px * (p_WCenter_W.z() - 1.0) / kDistance;
  const double r_px = f_px * kRadius / std::sqrt(kDistance * kDistance - kRadius * kRadius);
  double sum_u = 0.0, sum_v = 0.0, count = 0.0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (!IsRobotPixel(image.at(x, y))) continue;
      sum_u += x + 0.5, sum_v += y + 0.5, count += 1.0;
    }
  }
  ASSERT_GT(count, 0.0);
  EXPECT_NEAR(sum_u / count, u, 0.5);
  EXPECT_NEAR(sum_v / count, v, 0.5);
  // Area within 3 %: edge pixels are blended with the background.
  EXPECT_NEAR(count, std::numbers::pi * r_px * r_px, 0.03 * std::numbers::pi * r_px * r_px);
}

TEST_F(SceneRendererTest, EmptySceneIsTheNeutralBackgroundAndSizesAreChecked) {
  const Floor out_of_sight{.z = -1000.0, .center_W = Eigen::Vector2d::Zero(), .radius = 1.0};
  const Image image = renderer_.Render(Scene{}, out_of_sight, Camera{}, 64, 48);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) ASSERT_FALSE(IsRobotPixel(image.at(x, y)));
  EXPECT_GT(image.at(10, 10)[0], 200);
  EXPECT_THROW(renderer_.Render(Scene{}, out_of_sight, Camera{}, 0, 48), std::invalid_argument);
  EXPECT_THROW(renderer_.Render(Scene{}, out_of_sight, Camera{}, 64, SceneRenderer::kMaxSize + 1),
               std::invalid_argument);
}

// A box drawn from its mesh (12 triangles, flat normals) looks like the box
// primitive: the same pixels up to the antialiased edges.
TEST_F(SceneRendererTest, BoxMeshLooksLikeTheBoxPrimitive) {
  const Eigen::Vector3d edges(0.6, 0.3, 0.4);
  Camera camera;
  camera.p_WEye_W = Eigen::Vector3d(1.5, -2.0, 1.5);
  camera.p_WTarget_W = Eigen::Vector3d(0, 0, 0.4);
  Scene box, mesh;
  ScenePrimitive p;
  p.kind = Shape::Kind::kBox;
  p.size = edges;
  p.X_WG.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(0.3, 0.2, 1.0).normalized()).toRotationMatrix();
  p.X_WG.translation() = Eigen::Vector3d(0.1, 0.0, 0.5);
  p.color = Eigen::Vector3f(0.2f, 0.4f, 0.8f);
  box.primitives.push_back(p);
  p.kind = Shape::Kind::kMesh;
  p.size = Eigen::Vector3d::Ones();
  p.mesh = std::make_shared<const TriangleMesh>(testing::BoxMesh(edges));
  mesh.primitives.push_back(p);
  ASSERT_LT(testing::RelativeError(Eigen::MatrixXd::Map(mesh.BoundingPoints().data()->data(), 3, 8),
                                   Eigen::MatrixXd::Map(box.BoundingPoints().data()->data(), 3, 8)),
            1e-12);
  const Floor floor = FitFloor(box.BoundingPoints());
  const Image a = renderer_.Render(box, floor, camera, 200, 150), b = renderer_.Render(mesh, floor, camera, 200, 150);
  int robot = 0, different = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      robot += IsRobotPixel(a.at(x, y));
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
      different += d > 8;
    }
  }
  EXPECT_GT(robot, 1000);
  EXPECT_LT(different, robot / 50) << robot << " box pixels";
}

// The floor lies at z = 0, where the robot stands, even when a link reaches
// below it.
TEST(FitFloorTest, FloorIsAtZeroWhereTheRobotStands) {
  const std::vector<Eigen::Vector3d> points{{0.0, 0.0, -0.4}, {1.0, 0.5, 1.2}, {-0.2, 0.3, 0.1}};
  const Floor floor = FitFloor(points);
  EXPECT_EQ(floor.z, 0.0);
  EXPECT_NEAR(floor.center_W.x(), 0.4, 1e-15);
  EXPECT_NEAR(floor.center_W.y(), 0.25, 1e-15);
  EXPECT_GT(floor.radius, 1.2);  // wider than the points' height above it
}

// A post that stands on the floor and goes 0.3 m through it: seen from above,
// the part below z = 0 still shows (through the floor), so the post's pixels
// are as many as with no floor in sight; and where the floor hides it, its
// pixels are paler than above the floor.
TEST_F(SceneRendererTest, LinkBelowTheFloorShowsThroughIt) {
  constexpr int kWidth = 240, kHeight = 240;
  Camera camera;
  camera.p_WEye_W = Eigen::Vector3d(0.0, -3.0, 2.0);
  camera.p_WTarget_W = Eigen::Vector3d(0.0, 0.0, 0.1);
  Scene scene;
  ScenePrimitive post;
  post.kind = Shape::Kind::kBox;
  post.size = Eigen::Vector3d(0.2, 0.2, 0.9);
  post.X_WG.translation() = Eigen::Vector3d(0.0, 0.0, 0.15);  // z from -0.3 to 0.6
  post.color = Eigen::Vector3f(0.9f, 0.1f, 0.1f);
  scene.primitives.push_back(post);
  const Floor floor = FitFloor(scene.BoundingPoints());
  ASSERT_EQ(floor.z, 0.0);
  const Floor out_of_sight{.z = -1000.0, .center_W = Eigen::Vector2d::Zero(), .radius = 1.0};
  const Image with_floor = renderer_.Render(scene, floor, camera, kWidth, kHeight);
  const Image without = renderer_.Render(scene, out_of_sight, camera, kWidth, kHeight);
  const testing::PixelBox a = testing::RobotBox(with_floor, 0, 0, kWidth, kHeight);
  const testing::PixelBox b = testing::RobotBox(without, 0, 0, kWidth, kHeight);
  ASSERT_GT(b.count, 1000);
  EXPECT_NEAR(static_cast<double>(a.count), static_cast<double>(b.count), 0.03 * static_cast<double>(b.count));
  EXPECT_EQ(a.y1, b.y1);  // the post's lowest row, below the floor line, is drawn
  // The bottom of the post (under the floor) against its top (above it): the
  // red channel's lead over green is smaller through the floor.
  const auto lead = [&](int y) {
    const std::uint8_t* p = with_floor.at((a.x0 + a.x1) / 2, y);
    return int(p[0]) - int(p[1]);
  };
  const auto lead_without = [&](int y) {
    const std::uint8_t* p = without.at((b.x0 + b.x1) / 2, y);
    return int(p[0]) - int(p[1]);
  };
  EXPECT_LT(lead(a.y1 - 2), lead_without(b.y1 - 2) - 20);
  EXPECT_NEAR(lead(a.y0 + 2), lead_without(b.y0 + 2), 3);
}

}  // namespace
}  // namespace idbench
