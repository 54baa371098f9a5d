#include "idbench/render/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace idbench {
namespace {

// Normalised device coordinates of p_W.
Eigen::Vector3d Ndc(const Camera& camera, double aspect, const Eigen::Vector3d& p_W) {
  const Eigen::Vector4d clip = camera.Projection(aspect) * camera.View() * p_W.homogeneous();
  return clip.head<3>() / clip.w();
}

TEST(CameraTest, ViewMapsEyeToOriginAndTargetOntoMinusZ) {
  Camera camera;
  camera.p_WEye_W = Eigen::Vector3d(1, -3, 2);
  camera.p_WTarget_W = Eigen::Vector3d(0.5, 0.2, 0.7);
  const Eigen::Matrix4d X_CW = camera.View();
  EXPECT_LT((X_CW * camera.p_WEye_W.homogeneous()).head<3>().norm(), 1e-12);
  const Eigen::Vector3d target_C = (X_CW * camera.p_WTarget_W.homogeneous()).head<3>();
  const double distance = (camera.p_WTarget_W - camera.p_WEye_W).norm();
  EXPECT_LT((target_C - Eigen::Vector3d(0, 0, -distance)).norm(), 1e-12);
  // A rotation: orthonormal rows.
  EXPECT_LT((X_CW.topLeftCorner<3, 3>() * X_CW.topLeftCorner<3, 3>().transpose() - Eigen::Matrix3d::Identity()).norm(),
            1e-12);
}

TEST(CameraTest, FitKeepsEveryPointInViewAndFillsIt) {
  // The corners of a tall box off the origin, seen at two aspects.
  std::vector<Eigen::Vector3d> points;
  for (int c = 0; c < 8; ++c) points.emplace_back(1.0 + (c & 1) * 0.6, -0.5 + (c & 2) * 0.4, (c & 4) * 0.5);
  for (double aspect : {4.0 / 3.0, 0.5}) {
    const CameraView view;
    const Camera camera = FitCamera(points, aspect, view);
    double extent = 0.0;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d ndc = Ndc(camera, aspect, p);
      EXPECT_LE(std::abs(ndc.x()), 1.0 / (1.0 + view.margin) + 1e-9) << "aspect " << aspect;
      EXPECT_LE(std::abs(ndc.y()), 1.0 / (1.0 + view.margin) + 1e-9) << "aspect " << aspect;
      EXPECT_GT(ndc.z(), -1.0);
      EXPECT_LT(ndc.z(), 1.0);
      extent = std::max({extent, std::abs(ndc.x()), std::abs(ndc.y())});
    }
    // Conservative, but not wasteful: the points reach past half the frame.
    EXPECT_GT(extent, 0.5) << "aspect " << aspect;
  }
}

TEST(CameraTest, FitRejectsNoPoints) {
  EXPECT_THROW(FitCamera({}, 1.0), std::invalid_argument);
  EXPECT_THROW(FitCamera({Eigen::Vector3d::Zero()}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
