// A perspective camera in the world frame W (z up), and the fit that keeps a
// set of points (all poses of a figure) in view.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace idbench {

struct Camera {
  Eigen::Vector3d p_WEye_W = Eigen::Vector3d(4.0, -4.0, 2.0);  // eye position [m]
  Eigen::Vector3d p_WTarget_W = Eigen::Vector3d::Zero();       // look-at point [m]
  Eigen::Vector3d up_W = Eigen::Vector3d::UnitZ();            // image-up hint (unit)
  double fov_y = 0.5;                                           // vertical field of view [rad]
  double near = 0.1, far = 100.0;                               // clip distances [m]

  // World → camera (OpenGL: looking along −z) and camera → clip matrices.
  Eigen::Matrix4d View() const;
  Eigen::Matrix4d Projection(double aspect) const;
};

// Where the camera looks from: azimuth about world z from +x, elevation above
// the horizontal plane.
struct CameraView {
  double azimuth = -1.05;   // [rad]; −60°: from the front right of a robot reaching along +x
  double elevation = 0.38;  // [rad]; ≈ 22°
  double fov_y = 0.5;       // [rad]
  double margin = 0.08;     // free border, as a fraction of the image half-size
};

// The camera looking from `view` that keeps every point inside an image of
// the given aspect (width / height), centred on their extent. Conservative:
// each point is treated as if it were at the nearest depth. Throws
// std::invalid_argument if points is empty or aspect <= 0.
Camera FitCamera(const std::vector<Eigen::Vector3d>& points, double aspect, const CameraView& view = {});

}  // namespace idbench
