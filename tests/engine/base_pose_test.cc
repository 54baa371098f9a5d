#include "idbench/engine/base_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/test_util.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

using testing::RandomVector;

TEST(BasePoseTest, ParsesSixNumbersAndRefusesTheRest) {
  BasePose pose;
  std::string why;
  ASSERT_TRUE(ParseBasePose("0.1,-2,3e-1,3.141592653589793,0,-0.5", &pose, &why)) << why;
  EXPECT_EQ(pose.xyz_rpy, (std::array<double, 6>{0.1, -2, 0.3, std::numbers::pi, 0, -0.5}));
  for (const char* bad : {"", "1,2,3,4,5", "1,2,3,4,5,6,7", "1,2,3,4,5,x", "1,,3,4,5,6", "nan,0,0,0,0,0",
                          "0,0,0,0,0,1e9"}) {
    BasePose untouched;
    EXPECT_FALSE(ParseBasePose(bad, &untouched, &why)) << bad;
    EXPECT_TRUE(untouched.IsIdentity()) << bad;
  }
  EXPECT_NE(why.find("base_pose.yaw"), std::string::npos) << why;
}

// X_WR as URDF's <origin xyz rpy>: the rotation RotationFromRpy gives, then the translation.
TEST(BasePoseTest, PoseIsTheUrdfOrigin) {
  const BasePose pose{{0.3, -0.1, 2.0, 0.4, -0.7, 1.9}};
  const Eigen::Isometry3d X = pose.X_WR();
  EXPECT_TRUE(X.linear().isApprox(RotationFromRpy(Eigen::Vector3d(0.4, -0.7, 1.9)), 1e-15));
  EXPECT_TRUE(X.translation().isApprox(Eigen::Vector3d(0.3, -0.1, 2.0), 1e-15));
}

// Gravity seen from the base: upside down it points up the base's z; on a
// wall (pitch π/2) along the base's x; a turn about the vertical or a
// translation changes nothing.
TEST(BasePoseTest, GravityTurnsWithTheBase) {
  const RobotModel puma = MakePuma560();
  const double g = puma.gravity_W().norm();
  EXPECT_TRUE(MountRobot(puma, BasePose{{0, 0, 2.5, std::numbers::pi, 0, 0}})
                  .gravity_W()
                  .isApprox(Eigen::Vector3d(0, 0, g), 1e-12));
  EXPECT_TRUE(MountRobot(puma, BasePose{{0, 0, 1, 0, std::numbers::pi / 2, 0}})
                  .gravity_W()
                  .isApprox(Eigen::Vector3d(g, 0, 0), 1e-12));
  EXPECT_TRUE(MountRobot(puma, BasePose{{1, 2, 3, 0, 0, 0.8}}).gravity_W().isApprox(puma.gravity_W(), 1e-15));
  EXPECT_TRUE(IsMountedAt(puma, BasePose{}));
  EXPECT_FALSE(IsMountedAt(puma, BasePose{{0, 0, 0, std::numbers::pi, 0, 0}}));
  const BasePose wall{{0, 0, 1, 0.3, 1.2, -0.4}};
  const RobotModel mounted = MountRobot(puma, wall);
  EXPECT_TRUE(IsMountedAt(mounted, wall));
  EXPECT_TRUE(MountRobot(mounted, wall).gravity_W().isApprox(mounted.gravity_W(), 1e-15));  // idempotent
}

// The mounted model's gravity torque is the gradient of the potential energy
// in the world, V = Σ m_i |g| z_W(Bcm_i) with the centres of mass placed by
// X_WR (central differences, h = 1e-6: truncation ~h² |d³V/dq³| ≈ 1e-10 N m,
// rounding ~ε |V| / h ≈ 1e-8 N m).
TEST(BasePoseTest, MountedGravityTorqueIsTheWorldPotentialGradient) {
  const RobotModel puma = MakePuma560();
  const BasePose pose{{0, 0, 1.5, 2.1, -0.6, 0.3}};
  const Eigen::Isometry3d X_WR = pose.X_WR();
  const RobotModel mounted = MountRobot(puma, pose);
  const double g = puma.gravity_W().norm();
  RobotData d(mounted);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  auto potential = [&](const Eigen::VectorXd& q) {
    InverseDynamics(mounted, q, zero, zero, &d);
    double V = 0.0;
    for (int b = 0; b < 6; ++b) V += mounted.link(b).inertia.mass * g * (X_WR * d.p_WBcm_W[static_cast<size_t>(b)]).z();
    return V;
  };
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = RandomVector(6, 2.0, &rng);
    const Eigen::VectorXd tau = InverseDynamics(mounted, q, zero, zero, &d);
    for (int j = 0; j < 6; ++j) {
      const double h = 1e-6;
      Eigen::VectorXd qp = q, qm = q;
      qp[j] += h, qm[j] -= h;
      EXPECT_NEAR(tau[j], (potential(qp) - potential(qm)) / (2 * h), 1e-6) << "joint " << j + 1;
    }
  }
}

}  // namespace
}  // namespace idbench
