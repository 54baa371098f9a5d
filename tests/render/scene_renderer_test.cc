#include "idbench/render/scene_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "idbench/render/osmesa_context.h"
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

}  // namespace
}  // namespace idbench
