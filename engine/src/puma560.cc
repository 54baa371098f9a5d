#include "idbench/engine/puma560.h"

#include <array>
#include <cmath>
#include <numbers>

namespace idbench {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// One row of Corke's mdl_puma560 (standard DH, SI units, link-side values in
// DH frame i, motor-side drive values).
struct DhLink {
  double d, a, alpha;                // DH geometry [m, m, rad]
  double mass;                       // [kg]
  std::array<double, 3> r;           // centre of mass in DH frame i [m]
  std::array<double, 3> I;           // principal inertias Ixx, Iyy, Izz about the COM [kg m²]
  double Jm, G, B;                   // motor inertia [kg m²], gear ratio, motor viscous [N m s/rad]
  std::array<double, 2> Tc;          // motor Coulomb friction (+, −) [N m]
  std::array<double, 2> qlim;        // joint limits [deg]
};

constexpr std::array<DhLink, 6> kPuma{{
    // Link 1: mass and Ixx, Izz are ours (see puma560.h); Iyy = 0.35 is published.
    {0.0, 0.0, kPi / 2, 10.0, {0, 0, 0}, {0.2, 0.35, 0.2}, 200e-6, -62.6111, 1.48e-3, {0.395, -0.435}, {-160, 160}},
    {0.0, 0.4318, 0.0, 17.4, {-0.3638, 0.006, 0.2275}, {0.13, 0.524, 0.539}, 200e-6, 107.815, 0.817e-3, {0.126, -0.071}, {-45, 225}},
    {0.15005, 0.0203, -kPi / 2, 4.8, {-0.0203, -0.0141, 0.070}, {0.066, 0.086, 0.0125}, 200e-6, -53.7063, 1.38e-3, {0.132, -0.105}, {-225, 45}},
    {0.4318, 0.0, kPi / 2, 0.82, {0, 0.019, 0}, {1.8e-3, 1.3e-3, 1.8e-3}, 33e-6, 76.0364, 71.2e-6, {11.2e-3, -16.9e-3}, {-110, 170}},
    {0.0, 0.0, -kPi / 2, 0.34, {0, 0, 0}, {0.3e-3, 0.4e-3, 0.3e-3}, 33e-6, 71.923, 82.6e-6, {9.26e-3, -14.5e-3}, {-100, 100}},
    {0.0, 0.0, 0.0, 0.09, {0, 0, 0.032}, {0.15e-3, 0.15e-3, 0.04e-3}, 33e-6, 76.686, 36.7e-6, {3.96e-3, -10.5e-3}, {-266, 266}},
}};

constexpr double kShoulderHeight = 0.672;  // [m]
constexpr double kShapeRadius = 0.04;      // [m], for drawing and clearance

// D_i = Tz(d)·Tx(a)·Rx(α): DH frame i in link i's (joint) frame.
Eigen::Isometry3d DhOffset(const DhLink& dh) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(dh.a, 0.0, dh.d);
  X.linear() = Eigen::AngleAxisd(dh.alpha, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return X;
}

// A cylinder from point a to point b of the link frame.
Shape Segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Shape s;
  s.kind = Shape::Kind::kCylinder;
  s.size = Eigen::Vector3d(kShapeRadius, kShapeRadius, (b - a).norm());
  s.X_BG.translation() = 0.5 * (a + b);
  s.X_BG.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b - a).toRotationMatrix();
  return s;
}

}  // namespace

RobotModel MakePuma560() {
  std::vector<Link> links(6);
  for (size_t i = 0; i < 6; ++i) {
    const DhLink& dh = kPuma[i];
    Link& link = links[i];
    link.name = "link" + std::to_string(i + 1);
    link.joint_name = "joint" + std::to_string(i + 1);
    link.parent = static_cast<int>(i) - 1;
    link.axis_J = Eigen::Vector3d::UnitZ();
    // Link i's frame = DH frame i−1 rotated by q_i: fixed in the parent at D_{i−1}.
    if (i == 0) {
      link.X_PJ.translation() = Eigen::Vector3d(0.0, 0.0, kShoulderHeight);
    } else {
      link.X_PJ = DhOffset(kPuma[i - 1]);
    }
    link.limits.q_min = dh.qlim[0] * kDeg;
    link.limits.q_max = dh.qlim[1] * kDeg;
    // Drive terms reflected to the joint: Ia = G² Jm, Fv = G² B, Fc = |G| mean|Tc|.
    link.dynamics.rotor_inertia = dh.G * dh.G * dh.Jm;
    link.dynamics.viscous = dh.G * dh.G * dh.B;
    link.dynamics.coulomb = std::abs(dh.G) * 0.5 * (std::abs(dh.Tc[0]) + std::abs(dh.Tc[1]));
    // Mass properties from DH frame i into the link frame.
    const Eigen::Isometry3d X_BF = DhOffset(dh);
    link.inertia.mass = dh.mass;
    link.inertia.p_BoBcm_B = X_BF * Eigen::Vector3d(dh.r[0], dh.r[1], dh.r[2]);
    link.inertia.I_Bcm_B =
        X_BF.linear() * Eigen::Vector3d(dh.I[0], dh.I[1], dh.I[2]).asDiagonal() * X_BF.linear().transpose();
    // Drawn as the DH segments: along z by d, then along x by a.
    const Eigen::Vector3d p_d(0.0, 0.0, dh.d), p_a(dh.a, 0.0, dh.d);
    if (dh.d != 0.0) link.shapes.push_back(Segment(Eigen::Vector3d::Zero(), p_d));
    if (dh.a != 0.0) link.shapes.push_back(Segment(p_d, p_a));
    if (link.shapes.empty()) {
      // A joint housing around the axis.
      link.shapes.push_back(Segment(Eigen::Vector3d(0, 0, -0.06), Eigen::Vector3d(0, 0, 0.06)));
    }
  }
  return RobotModel("puma560", std::move(links));
}

}  // namespace idbench
