// The seed paper's 6-DOF robot (paper-method.md): six homogeneous steel
// cylinders B1..B6 joined by hinges O1..O6, the embedded default robot.
#pragma once

#include <array>

#include "idbench/engine/robot_model.h"

namespace idbench {

struct Paper6rGeometry {
  static constexpr double kDensity = 7801.0;  // steel [kg/m³]
  std::array<double, 6> length{1.045, 1.245, 1.21, 0.315, 0.29, 0.3};  // l_i [m]
  std::array<double, 6> radius{0.5, 0.3, 0.2, 0.2, 0.2, 0.3};          // R_i [m]
};

// Builds paper6r. Link frame B_i: origin at the inboard hinge O_i, x along the
// cylinder axis (e1 of the paper), so the centroid is at (l_i/2, 0, 0) and the
// inertia is diag(J11, J22, J33) with J11 = m R²/2, J22 = J33 = m (3R² + l²)/12.
// Initial pose (q = 0): B1, B2 vertical; B3..B6 horizontal along world x;
// hinge axes O1: world z, O2: y, O3: y, O4: along B3, O5: y, O6: along B5.
RobotModel MakePaper6r(const Paper6rGeometry& geometry = {});

}  // namespace idbench
