#include "idbench/ident/physically_consistent.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <stdexcept>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {
namespace {

using testing::RelativeError;

// The 10 parameters about Bo of a solid box of mass m and edge lengths
// `edges` along the axes of a frame C, R_BC its orientation and c = p_BoBcm_B
// its centroid: I_Bo = R_BC I_C R_BCᵀ + m (cᵀc 𝟙 − c cᵀ).
InertialParameters BoxParameters(double m, const Eigen::Vector3d& edges, const Eigen::Matrix3d& R_BC,
                                 const Eigen::Vector3d& c) {
  const Eigen::Vector3d e2 = edges.cwiseAbs2();
  const Eigen::Matrix3d I_C =
      (m / 12.0) * Eigen::Vector3d(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y()).asDiagonal();
  const Eigen::Matrix3d I =
      R_BC * I_C * R_BC.transpose() + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  InertialParameters pi;
  pi << m, m * c, I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
  return pi;
}

Eigen::Matrix3d SomeRotation() {
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
}

TEST(PseudoInertiaTest, BoxPseudoInertiaIsItsSecondMomentAndPositiveDefinite) {
  const double m = 3.5;
  const Eigen::Vector3d edges(0.4, 0.1, 0.25), c(0.3, -0.2, 0.15);
  const Eigen::Matrix3d R_BC = SomeRotation();
  const InertialParameters pi = BoxParameters(m, edges, R_BC, c);
  // Independent truth: ∫ r rᵀ dm over the box = m (R_BC diag(e²/12) R_BCᵀ + c cᵀ).
  Eigen::Matrix4d J_expected;
  J_expected.topLeftCorner<3, 3>() =
      m * (R_BC * (edges.cwiseAbs2() / 12.0).asDiagonal() * R_BC.transpose() + c * c.transpose());
  J_expected.topRightCorner<3, 1>() = m * c;
  J_expected.bottomLeftCorner<1, 3>() = m * c.transpose();
  J_expected(3, 3) = m;
  const Eigen::Matrix4d J = PseudoInertia(pi);
  EXPECT_LT(RelativeError(J, J_expected), 1e-14);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(J).eigenvalues()[0], 0.0);
  EXPECT_NEAR(MinPseudoInertiaEigenvalues(pi, 1)[0], Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(J_expected).eigenvalues()[0],
              1e-14 * m);
}

TEST(PseudoInertiaTest, TriangleViolatingInertiaIsNotPositiveSemidefinite) {
  // PUMA 560 link 3 as published: principal moments 0.066, 0.086, 0.0125 kg m²
  // about the centre of mass, 0.066 + 0.0125 < 0.086. J ⪰ 0 ⇔ Σ_cm ⪰ 0, and
  // Σ_cm = ½ tr(I) 𝟙 − I has the eigenvalue (0.066 + 0.0125 − 0.086)/2 = −0.00375.
  const double m = 4.8;
  const Eigen::Vector3d c(-0.0203, -0.0141, 0.070);
  auto body = [&](double Iyy) {
    const Eigen::Matrix3d I = Eigen::Vector3d(0.066, Iyy, 0.0125).asDiagonal();
    const Eigen::Matrix3d I_Bo = I + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    InertialParameters pi;
    pi << m, m * c, I_Bo(0, 0), I_Bo(0, 1), I_Bo(1, 1), I_Bo(0, 2), I_Bo(1, 2), I_Bo(2, 2);
    return pi;
  };
  const InertialParameters puma3 = body(0.086);
  EXPECT_LT(MinPseudoInertiaEigenvalues(puma3, 1)[0], -1e-3);
  // On the boundary (Iyy = Ixx + Izz) the smallest eigenvalue is zero.
  EXPECT_NEAR(MinPseudoInertiaEigenvalues(body(0.0785), 1)[0], 0.0, 1e-14);
  // The model file keeps the published values: its link 3 is inconsistent too.
  const Eigen::VectorXd pi_puma = StandardParameters(MakePuma560(), FrictionModel{});
  const Eigen::VectorXd min_eigenvalue = MinPseudoInertiaEigenvalues(pi_puma, 6);
  EXPECT_LT(min_eigenvalue[2], 0.0);
  for (int l : {0, 1, 3, 4, 5}) EXPECT_GT(min_eigenvalue[l], 0.0) << "link " << l + 1;
}

TEST(PseudoInertiaTest, RejectsTheWrongNumberOfParameters) {
  EXPECT_THROW(PseudoInertia(Eigen::VectorXd::Zero(9)), std::invalid_argument);
  EXPECT_THROW(MinPseudoInertiaEigenvalues(Eigen::VectorXd::Zero(19), 2), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
