#include "idbench/engine/transmission.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

namespace idbench {
namespace {

// The Stäubli TX40's: N = [32, 32, 45, −48, 45, 32], motor 6 turns with joint 5.
Transmission Tx40() {
  Transmission t = Transmission::FromReduction({32, 32, 45, -48, 45, 32});
  t.actuator_from_joint(5, 4) = 32;
  t.joint_offset = Eigen::VectorXd::Zero(6);
  t.joint_offset[1] = -1.5707963267948966;
  t.joint_offset[2] = 1.5707963267948966;
  return t;
}

TEST(TransmissionTest, VirtualWorkAndRoundTrips) {
  const Transmission t = Tx40();
  ASSERT_TRUE(t.IsValid(6, nullptr));
  const Eigen::MatrixXd qd = Eigen::MatrixXd::Random(50, 6), tau_m = Eigen::MatrixXd::Random(50, 6);
  // θ̇m = A·q̇ row by row, written out for the wrist: θ̇m6 = N6·(q̇5 + q̇6).
  Eigen::MatrixXd thetad_m = qd * t.actuator_from_joint.transpose();
  EXPECT_NEAR(thetad_m(7, 5), 32 * (qd(7, 4) + qd(7, 5)), 1e-13);
  EXPECT_LT((t.JointRates(thetad_m) - qd).cwiseAbs().maxCoeff(), 1e-14);
  // Virtual work: τᵀq̇ = τmᵀθ̇m per sample, τ5 = N5·τm5 + N6·τm6.
  const Eigen::MatrixXd tau = t.JointTorques(tau_m);
  EXPECT_NEAR(tau(3, 4), 45 * tau_m(3, 4) + 32 * tau_m(3, 5), 1e-13);
  for (Eigen::Index s = 0; s < 50; ++s) {
    const double joint = tau.row(s).dot(qd.row(s)), motor = tau_m.row(s).dot(thetad_m.row(s));
    EXPECT_NEAR(joint, motor, 1e-12 * std::max(1.0, std::abs(motor)));
  }
  // q = A⁻¹·θm + q0 undoes θm = A·(q − q0).
  const Eigen::MatrixXd q = Eigen::MatrixXd::Random(50, 6);
  const Eigen::MatrixXd theta_m = (q.rowwise() - t.joint_offset.transpose()) * t.actuator_from_joint.transpose();
  EXPECT_LT((t.JointPositions(theta_m) - q).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(TransmissionTest, SingleMotorJointsAndCoupledOnes) {
  const Transmission t = Tx40();
  for (int j = 0; j < 4; ++j) {
    ASSERT_TRUE(t.SingleMotorOf(j).has_value()) << j;
    EXPECT_EQ(t.SingleMotorOf(j)->motor, j);
    EXPECT_EQ(t.SingleMotorOf(j)->ratio, t.actuator_from_joint(j, j));
  }
  EXPECT_FALSE(t.SingleMotorOf(4).has_value());  // motors 5 and 6 turn it
  EXPECT_FALSE(t.SingleMotorOf(5).has_value());  // motor 6 turns with joint 5 too
}

TEST(TransmissionTest, InvalidOnesNameTheField) {
  std::string why;
  Transmission t = Tx40();
  EXPECT_FALSE(t.IsValid(5, &why));
  EXPECT_EQ(why, "actuator_from_joint: expected 5 × 5 (one row per actuator, one column per joint), got 6 × 6");
  t.actuator_from_joint.row(5) = t.actuator_from_joint.row(4);
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why.rfind("actuator_from_joint: not invertible", 0), 0u) << why;
  t = Tx40();
  t.actuator_from_joint(0, 0) = NAN;
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why, "actuator_from_joint: expected finite numbers");
  t = Tx40();
  t.joint_offset.resize(3);
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why, "joint_offset: expected 6 values, got 3");
}

// Gear ratios are bounded as drive gains are (kMaxRatio = 1e4 either way):
// 1e77 overflowed the regressor's N² (a segfault in the base-parameter QR),
// 1e5 silently halved the base set. The bound itself is accepted.
TEST(TransmissionTest, GearRatiosBeyondAnyDriveAreRefused) {
  std::string why;
  Transmission t = Tx40();
  t.actuator_from_joint(2, 2) = 1e77;
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why, "actuator_from_joint[2][2]: 1e+77 rad of motor 3 per rad of joint 3, beyond any drive (a gear ratio "
                 "of magnitude at most 10000)");
  t.actuator_from_joint(2, 2) = -1e5;
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why.rfind("actuator_from_joint[2][2]: -100000 rad of motor 3", 0), 0u) << why;
  t.actuator_from_joint(2, 2) = -Transmission::kMaxRatio;
  EXPECT_TRUE(t.IsValid(6, &why)) << why;
  t = Transmission::FromReduction({1, 1, 1e-5, 1, 1, 1});  // joint 3 turning 1e5 rad per motor rad
  EXPECT_FALSE(t.IsValid(6, &why));
  EXPECT_EQ(why, "actuator_from_joint: smallest singular value 1e-05, below 1/10000: a joint would turn more than "
                 "10000 rad per rad of its motors, beyond any drive");
  t = Transmission::FromReduction({1, 1, 1.0 / Transmission::kMaxRatio, 1, 1, 1});
  EXPECT_TRUE(t.IsValid(6, &why)) << why;
}

}  // namespace
}  // namespace idbench
