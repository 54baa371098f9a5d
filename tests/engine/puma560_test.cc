#include "idbench/engine/puma560.h"

#include <gtest/gtest.h>

#include <numbers>

#include "engine/test_util.h"
#include "idbench/engine/inverse_dynamics.h"

namespace idbench {
namespace {

constexpr double kPi = std::numbers::pi;

// Corke's DH chain, written independently: T = Π Rz(θ)·Tz(d)·Tx(a)·Rx(α).
Eigen::Isometry3d DhForwardKinematics(const Eigen::VectorXd& q) {
  const double d[6] = {0, 0, 0.15005, 0.4318, 0, 0};
  const double a[6] = {0, 0.4318, 0.0203, 0, 0, 0};
  const double alpha[6] = {kPi / 2, 0, -kPi / 2, kPi / 2, -kPi / 2, 0};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) {
    T = T * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(a[i], 0, d[i]) *
        Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX());
  }
  return T;
}

TEST(Puma560Test, ForwardKinematicsMatchesTheDhChain) {
  const RobotModel model = MakePuma560();
  RobotData data(model);
  const Eigen::Vector3d shoulder(0, 0, 0.672);
  // Corke: p560.fkine(qz) = transl(0.4521, -0.1500, 0.4318) (0.15005 exactly).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(model, zero, zero, zero, &data);
  EXPECT_NEAR((data.p_WBo_W[5] - shoulder - Eigen::Vector3d(0.4521, -0.15005, 0.4318)).norm(), 0.0, 1e-12);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = testing::RandomVector(6, 3.0, &rng);
    ComputeKinematics(model, q, zero, zero, &data);
    const Eigen::Isometry3d T = DhForwardKinematics(q);
    // Link 6's frame is DH frame 5 rotated by q6, which DH frame 6 equals (d6 = a6 = α6 = 0).
    EXPECT_LT((data.R_WB[5] - T.linear()).norm(), 1e-12);
    EXPECT_LT((data.p_WBo_W[5] - shoulder - T.translation()).norm(), 1e-12);
  }
}

// Published values of Corke's model (Robotics, Vision and Control):
// p560.gravload(qz) = [0 37.4837 0.2489 0 0 0] N m, computed with g = 9.81;
// idbench uses standard gravity 9.80665, and gravity torques scale with g.
TEST(Puma560Test, GravityTorquesMatchThePublishedModel) {
  const RobotModel model = MakePuma560();
  RobotData data(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  const Eigen::VectorXd tau = InverseDynamics(model, zero, zero, zero, &data);
  Eigen::VectorXd expected(6);
  expected << 0, 37.4837, 0.2489, 0, 0, 0;
  expected *= 9.80665 / 9.81;
  EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(), 6e-5) << tau.transpose();
}

TEST(Puma560Test, LimitsAndDriveParameters) {
  const RobotModel model = MakePuma560();
  EXPECT_NEAR(model.link(1).limits.q_min, -45.0 * kPi / 180.0, 1e-15);
  EXPECT_NEAR(model.link(2).limits.q_min, -225.0 * kPi / 180.0, 1e-15);
  // Ia = G² Jm for joint 2: 107.815² · 200e-6.
  EXPECT_NEAR(model.link(1).dynamics.rotor_inertia, 107.815 * 107.815 * 200e-6, 1e-12);
  // Link 3 keeps its published, triangle-violating inertia: one warning, naming it.
  const std::vector<std::string> warnings = InertiaWarnings(model);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("link3"), std::string::npos);
}

}  // namespace
}  // namespace idbench
