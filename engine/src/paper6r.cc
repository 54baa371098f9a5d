#include "idbench/engine/paper6r.h"

#include <cmath>
#include <numbers>

namespace idbench {

RobotModel MakePaper6r(const Paper6rGeometry& geometry) {
  // Orientation of each link frame in the world at q = 0 (columns: e1, e2, e3).
  // Vertical links: e1 = z, e2 = y, e3 = e1 × e2 = -x. Horizontal: identity.
  Eigen::Matrix3d R_W_vertical;
  R_W_vertical << 0, 0, -1,  //
      0, 1, 0,               //
      1, 0, 0;
  const Eigen::Matrix3d R_W_horizontal = Eigen::Matrix3d::Identity();
  const std::array<Eigen::Matrix3d, 6> R_WB0{R_W_vertical,   R_W_vertical,   R_W_horizontal,
                                             R_W_horizontal, R_W_horizontal, R_W_horizontal};
  // Hinge axes in the link's own frame: along the cylinder (e1) or e2.
  const std::array<Eigen::Vector3d, 6> axis{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                            Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX(),
                                            Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()};

  std::vector<Link> links(6);
  for (int i = 0; i < 6; ++i) {
    const double l = geometry.length[static_cast<size_t>(i)];
    const double r = geometry.radius[static_cast<size_t>(i)];
    const double m = Paper6rGeometry::kDensity * std::numbers::pi * r * r * l;
    Link& link = links[static_cast<size_t>(i)];
    link.name = "B" + std::to_string(i + 1);
    link.joint_name = "O" + std::to_string(i + 1);
    link.parent = i - 1;
    link.axis_J = axis[static_cast<size_t>(i)];
    // Joint frame in the parent: at the parent's outboard end (or the world
    // origin for O1), rotated so that J = B at q = 0.
    const Eigen::Matrix3d R_WP = i == 0 ? Eigen::Matrix3d::Identity() : R_WB0[static_cast<size_t>(i - 1)];
    link.X_PJ.linear() = R_WP.transpose() * R_WB0[static_cast<size_t>(i)];
    link.X_PJ.translation() =
        i == 0 ? Eigen::Vector3d::Zero()
               : Eigen::Vector3d(geometry.length[static_cast<size_t>(i - 1)], 0.0, 0.0);
    link.inertia.mass = m;
    link.inertia.p_BoBcm_B = Eigen::Vector3d(l / 2.0, 0.0, 0.0);
    const double J11 = m * r * r / 2.0;
    const double J22 = m * (3.0 * r * r + l * l) / 12.0;
    link.inertia.I_Bcm_B = Eigen::Vector3d(J11, J22, J22).asDiagonal();
    // Cylinder along x of B: rotate the shape's z axis onto B's x axis.
    Shape cylinder;
    cylinder.kind = Shape::Kind::kCylinder;
    cylinder.size = Eigen::Vector3d(r, r, l);
    cylinder.X_BG.linear() =
        Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    cylinder.X_BG.translation() = link.inertia.p_BoBcm_B;
    link.shapes.push_back(cylinder);
  }
  return RobotModel("paper6r", std::move(links));
}

}  // namespace idbench
