#include "idbench/render/camera.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace idbench {

Eigen::Matrix4d Camera::View() const {
  const Eigen::Vector3d back = (p_WEye_W - p_WTarget_W).normalized();  // camera +z
  const Eigen::Vector3d right = up_W.cross(back).normalized();         // camera +x
  const Eigen::Vector3d up = back.cross(right);                         // camera +y
  Eigen::Matrix4d X_CW = Eigen::Matrix4d::Identity();
  X_CW.block<1, 3>(0, 0) = right.transpose();
  X_CW.block<1, 3>(1, 0) = up.transpose();
  X_CW.block<1, 3>(2, 0) = back.transpose();
  X_CW.block<3, 1>(0, 3) = -X_CW.block<3, 3>(0, 0) * p_WEye_W;
  return X_CW;
}

Eigen::Matrix4d Camera::Projection(double aspect) const {
  const double f = 1.0 / std::tan(fov_y / 2.0);
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = f / aspect;
  P(1, 1) = f;
  P(2, 2) = (far + near) / (near - far);
  P(2, 3) = 2.0 * far * near / (near - far);
  P(3, 2) = -1.0;
  return P;
}

Camera FitCamera(const std::vector<Eigen::Vector3d>& points, double aspect, const CameraView& view) {
  if (points.empty()) throw std::invalid_argument("FitCamera: expected at least one point, got none");
  if (!(aspect > 0.0)) throw std::invalid_argument("FitCamera: expected aspect > 0, got " + std::to_string(aspect));
  // Camera axes: `back` points from the scene to the eye.
  const Eigen::Vector3d back(std::cos(view.elevation) * std::cos(view.azimuth),
                             std::cos(view.elevation) * std::sin(view.azimuth), std::sin(view.elevation));
  const Eigen::Vector3d right = Eigen::Vector3d::UnitZ().cross(back).normalized();
  const Eigen::Vector3d up = back.cross(right);
  // Extent of the points along the three axes.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d c(p.dot(right), p.dot(up), p.dot(back));
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Eigen::Vector3d mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  // Distance from the extent's centre so that the half-widths fit at the
  // nearest depth (mid.z + half.z), with the margin.
  const double tan_y = std::tan(view.fov_y / 2.0), tan_x = tan_y * aspect;
  const double fit = std::max(half.x() / tan_x, half.y() / tan_y) * (1.0 + view.margin);
  const double radius = half.norm();
  const double distance = std::max(half.z() + fit, 1e-3 + 1.5 * radius);
  Camera camera;
  camera.fov_y = view.fov_y;
  camera.p_WTarget_W = mid.x() * right + mid.y() * up + mid.z() * back;
  camera.p_WEye_W = camera.p_WTarget_W + distance * back;
  camera.up_W = Eigen::Vector3d::UnitZ();
  camera.near = std::max(1e-3, (distance - 3.0 * radius - 1.0) * 0.5);
  camera.far = distance + 6.0 * radius + 10.0;
  return camera;
}

}  // namespace idbench
