#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "engine/test_util.h"
#include "engine/urdf_test_util.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Roll-pitch-yaw ----

TEST(UrdfTest, RotationFromRpyIsFixedAxesXThenYThenZ) {
  const Eigen::Vector3d rpy(0.3, -1.1, 2.9);
  ExpectNear(RotationFromRpy(rpy), (Rz(rpy.z()) * Ry(rpy.y()) * Rx(rpy.x())).eval(), 1e-15, "R");
}

TEST(UrdfTest, RpyRoundTripsOnRandomRotations) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d(testing::RandomVector(4, 1.0, &rng)).normalized()).toRotationMatrix();
    const Eigen::Vector3d rpy = RpyFromRotation(R);
    EXPECT_LE(std::abs(rpy.y()), kPi / 2);
    ExpectNear(RotationFromRpy(rpy), R, 1e-14, "R, trial " + std::to_string(trial));
  }
  // Away from gimbal lock the angles themselves come back.
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector3d rpy = testing::RandomVector(3, 1.0, &rng);
    rpy.x() *= 3.1;
    rpy.y() *= 1.5;
    rpy.z() *= 3.1;
    ExpectNear(RpyFromRotation(RotationFromRpy(rpy)), rpy, 1e-13, "rpy, trial " + std::to_string(trial));
  }
}

// At pitch = ±π/2 only yaw ∓ roll is defined; just short of it the split is
// ill-conditioned. The rotation must still come back to rounding.
TEST(UrdfTest, RpyRoundTripsAtAndNearGimbalLock) {
  std::mt19937 rng(4);
  for (double pitch : {kPi / 2, -kPi / 2, kPi / 2 - 1e-7, -kPi / 2 + 1e-7, kPi / 2 - 1e-12, -kPi / 2 + 1e-13}) {
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector2d angles = testing::RandomVector(2, 3.1, &rng);  // roll, yaw
      // Through a quaternion, as rotations composed in kinematics come: the
      // tiny entries then carry absolute (not relative) rounding errors.
      const Eigen::Matrix3d R =
          Eigen::Quaterniond(Rz(angles[1]) * Ry(pitch) * Rx(angles[0])).toRotationMatrix();
      const Eigen::Vector3d rpy = RpyFromRotation(R);
      ExpectNear(RotationFromRpy(rpy), R, 1e-14, "R at pitch " + std::to_string(pitch));
      EXPECT_NEAR(rpy.y(), pitch, 1e-7);
    }
  }
  // Through URDF text and urdfdom's rpy → quaternion conversion.
  std::vector<Link> links = MakePaper6r().links();
  links[0].X_PJ.linear() = Rz(0.4) * Ry(kPi / 2) * Rx(-2.0);
  links[1].X_PJ.linear() = Rz(-3.0) * Ry(-kPi / 2 + 1e-9) * Rx(1.0);
  const RobotModel expected("gimbal", links);
  ExpectModelsNear(LoadUrdfString(WriteUrdf(expected)).model, expected, 1e-14);
}

}  // namespace
}  // namespace idbench
