#include "idbench/ident/joint_torque_regressor.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>


#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/ident/base_parameters.h"

namespace idbench {
namespace {

using testing::RandomVector;

// Every friction term; with `coupled`, on the actuator side of gears of 30
// where the last motor also turns with the joint before it.
FrictionModel AllFrictionTerms(int n_dof, bool coupled) {
  FrictionModel friction;
  friction.viscous = friction.coulomb = friction.offset = friction.rotor_inertia = true;
  if (!coupled) return friction;
  friction.actuator_from_joint = Eigen::MatrixXd::Identity(n_dof, n_dof) * 30.0;
  if (n_dof >= 2) friction.actuator_from_joint(n_dof - 1, n_dof - 2) = 30.0;
  return friction;
}

class JointTorqueRegressorTest : public ::testing::TestWithParam<int> {
 protected:
  RobotModel model_ = testing::MakeTestRobot(GetParam());
};

// Y(q, qd, qdd)·π equals the RNEA (an independent recursion) on random states.
TEST_P(JointTorqueRegressorTest, TimesParametersEqualsInverseDynamics) {
  RobotData d(model_);
  const FrictionModel none;
  const Eigen::VectorXd pi = StandardParameters(model_, none);
  ASSERT_EQ(pi.size(), 10 * model_.n_links());
  std::mt19937 rng(41);
  Eigen::MatrixXd Y;
  const int n = model_.n_dof();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                          qdd = RandomVector(n, 5.0, &rng);
    ComputeJointTorqueRegressor(model_, none, q, qd, qdd, &d, &Y);
    const Eigen::VectorXd tau = InverseDynamics(model_, q, qd, qdd, &d);
    EXPECT_LT(testing::RelativeError(Y * pi, tau), 1e-12) << "trial " << trial;
  }
}

TEST_P(JointTorqueRegressorTest, FrictionColumns) {
  RobotData d(model_);
  FrictionModel friction;
  friction.viscous = friction.coulomb = friction.offset = friction.rotor_inertia = true;
  const int n = model_.n_dof();
  Eigen::VectorXd pi = StandardParameters(model_, friction);
  ASSERT_EQ(pi.size(), 10 * model_.n_links() + 4 * n);
  const Eigen::VectorXd fv = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0), fc = Eigen::VectorXd::LinSpaced(n, 3.0, 4.0),
                        off = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0), ia = Eigen::VectorXd::LinSpaced(n, 0.1, 0.2);
  for (int j = 0; j < n; ++j) pi.segment<4>(10 * n + 4 * j) << fv[j], fc[j], off[j], ia[j];
  std::mt19937 rng(42);
  const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng), qdd = RandomVector(n, 5.0, &rng);
  Eigen::MatrixXd Y;
  ComputeJointTorqueRegressor(model_, friction, q, qd, qdd, &d, &Y);
  const Eigen::VectorXd expected = InverseDynamics(model_, q, qd, qdd, &d) + fv.cwiseProduct(qd) +
                                   fc.cwiseProduct(qd.cwiseSign()) + off + ia.cwiseProduct(qdd);
  EXPECT_LT(testing::RelativeError(Y * pi, expected), 1e-12);
  const std::vector<std::string> names = StandardParameterNames(model_, friction);
  EXPECT_EQ(names.size(), static_cast<size_t>(pi.size()));
  EXPECT_EQ(names[10 * n + 1], "Fc1");
}

// With the model's own friction and rotor inertia (puma560 has them), Y·π is
// what the motor supplies: RNEA plus the joint dynamics.
TEST_P(JointTorqueRegressorTest, StandardParametersCarryTheModelsJointDynamics) {
  RobotData d(model_);
  FrictionModel friction;
  friction.viscous = friction.coulomb = friction.rotor_inertia = true;
  const Eigen::VectorXd pi = StandardParameters(model_, friction);
  std::mt19937 rng(43);
  const int n = model_.n_dof();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                          qdd = RandomVector(n, 5.0, &rng);
    Eigen::MatrixXd Y;
    ComputeJointTorqueRegressor(model_, friction, q, qd, qdd, &d, &Y);
    Eigen::VectorXd expected = InverseDynamics(model_, q, qd, qdd, &d);
    AddJointDynamicsTorque(model_, qd, qdd, &expected);
    EXPECT_LT(testing::RelativeError(Y * pi, expected), 1e-12) << "trial " << trial;
  }
}

// π → model → π is the identity.
TEST_P(JointTorqueRegressorTest, ModelFromStandardParametersRoundTrip) {
  FrictionModel friction;
  friction.viscous = friction.coulomb = friction.rotor_inertia = true;
  Eigen::VectorXd pi = StandardParameters(model_, friction);
  pi.tail(3 * model_.n_dof()).setLinSpaced(0.1, 0.7);  // friction differs from the model's
  const RobotModel rebuilt = ModelWithStandardParameters(model_, friction, pi);
  EXPECT_LT(testing::RelativeError(StandardParameters(rebuilt, friction), pi), 1e-14);
  EXPECT_THROW(ModelWithStandardParameters(model_, friction, pi.head(5)), std::invalid_argument);
}

// ⟨G, Y⟩ without forming Y equals the sum over Y's entries, friction included.
TEST_P(JointTorqueRegressorTest, ContractionEqualsTheEntrywiseSum) {
  RobotData d(model_);
  FrictionModel friction;
  friction.viscous = friction.coulomb = friction.offset = friction.rotor_inertia = true;
  std::mt19937 rng(43);
  Eigen::MatrixXd Y;
  const int n = model_.n_dof();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                          qdd = RandomVector(n, 5.0, &rng);
    ComputeJointTorqueRegressor(model_, friction, q, qd, qdd, &d, &Y);
    Eigen::MatrixXd G(Y.rows(), Y.cols());
    for (Eigen::Index k = 0; k < G.size(); ++k) G.data()[k] = RandomVector(1, 1.0, &rng)[0];
    const double contracted = ContractJointTorqueRegressorT<double>(model_, friction, q, qd, qdd, G, &d);
    const double entrywise = (G.array() * Y.array()).sum();
    EXPECT_NEAR(contracted, entrywise, 1e-12 * (G.array().abs() * Y.array().abs()).sum()) << "trial " << trial;
  }
}

// Y(q, q̇, q̈) π without Y equals the product with Y, for arbitrary π (not a
// mechanism) with every friction term, joint side and coupled actuator side.
TEST_P(JointTorqueRegressorTest, TorqueOfParametersEqualsTheRegressorTimesThem) {
  RobotData d(model_);
  const int n = model_.n_dof();
  std::mt19937 rng(47);
  for (const FrictionModel& friction : {AllFrictionTerms(n, false), AllFrictionTerms(n, true)}) {
    Eigen::MatrixXd Y;
    Eigen::VectorXd tau;
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                            qdd = RandomVector(n, 5.0, &rng);
      const Eigen::VectorXd pi = RandomVector(NumStandardParameters(model_, friction), 1.0, &rng);
      ComputeJointTorqueRegressor(model_, friction, q, qd, qdd, &d, &Y);
      ComputeJointTorqueOfParameters(model_, friction, q, qd, qdd, pi, &d, &tau);
      EXPECT_LT((tau - Y * pi).norm(), 1e-12 * (Y.cwiseAbs() * pi.cwiseAbs()).norm())
          << (friction.actuator_side() ? "actuator side" : "joint side") << ", trial " << trial;
    }
  }
  Eigen::VectorXd tau;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  EXPECT_THROW(ComputeJointTorqueOfParameters(model_, FrictionModel{}, zero, zero, zero, zero, &d, &tau),
               std::invalid_argument);
}

// M(q) of arbitrary standard parameters (not a mechanism: random signs, the
// friction terms too) equals the q̈ coefficients of the regressor, column by
// column Y(q, 0, e_k) π − Y(q, 0, 0) π: on the joint side and on a coupled
// actuator side (rotor inertias through Aᵀ diag(Ia) A).
TEST_P(JointTorqueRegressorTest, JointSpaceInertiaEqualsTheRegressorsAccelerationColumns) {
  RobotData d(model_);
  const int n = model_.n_dof();
  std::mt19937 rng(46);
  const FrictionModel joint_side = AllFrictionTerms(n, false), actuator_side = AllFrictionTerms(n, true);
  for (const FrictionModel& friction : {joint_side, actuator_side}) {
    Eigen::MatrixXd Y, M, M_regressor(n, n);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng);
      const Eigen::VectorXd pi = RandomVector(NumStandardParameters(model_, friction), 1.0, &rng);
      ComputeJointTorqueRegressor(model_, friction, q, zero, zero, &d, &Y);
      const Eigen::VectorXd g = Y * pi;
      for (int k = 0; k < n; ++k) {
        ComputeJointTorqueRegressor(model_, friction, q, zero, Eigen::VectorXd::Unit(n, k), &d, &Y);
        M_regressor.col(k) = Y * pi - g;
      }
      ComputeKinematics(model_, q, qd, RandomVector(n, 5.0, &rng), &d);  // any q̇, q̈: only the poses count
      ComputeJointSpaceInertia(model_, friction, pi, d, &M);
      EXPECT_LT((M - M_regressor).norm(), 1e-12 * M_regressor.norm())
          << (friction.actuator_side() ? "actuator side" : "joint side") << ", trial " << trial;
      EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
    }
  }
  EXPECT_THROW(ComputeJointSpaceInertia(model_, joint_side, Eigen::VectorXd::Zero(3), d, nullptr),
               std::invalid_argument);
}

// A coupled actuator side: each motor k's terms on θ̇m_k = A_k·q̇ reach the
// joints through A_kᵀ, computed here motor by motor; the contraction agrees.
TEST_P(JointTorqueRegressorTest, ActuatorSideTermsEnterThroughTheTransposedTransmission) {
  RobotData d(model_);
  const int n = model_.n_dof();
  std::mt19937 rng(44);
  const FrictionModel friction = AllFrictionTerms(n, true);
  const int o = 10 * model_.n_links();
  Eigen::VectorXd pi = StandardParameters(model_, friction);
  const Eigen::VectorXd motor = RandomVector(4 * n, 1.0, &rng).cwiseAbs();
  pi.tail(4 * n) = motor;
  Eigen::MatrixXd Y;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                          qdd = RandomVector(n, 5.0, &rng);
    ComputeJointTorqueRegressor(model_, friction, q, qd, qdd, &d, &Y);
    Eigen::VectorXd tau = InverseDynamics(model_, q, qd, qdd, &d);
    const Eigen::VectorXd thd = friction.actuator_from_joint * qd, thdd = friction.actuator_from_joint * qdd;
    Eigen::VectorXd tau_m(n);
    for (int k = 0; k < n; ++k) {
      tau_m[k] = motor[4 * k] * thd[k] + motor[4 * k + 1] * ((thd[k] > 0) - (thd[k] < 0)) + motor[4 * k + 2] +
                 motor[4 * k + 3] * thdd[k];
    }
    tau += friction.actuator_from_joint.transpose() * tau_m;
    EXPECT_LT(testing::RelativeError(Y * pi, tau), 1e-12) << "trial " << trial;
    Eigen::MatrixXd G(Y.rows(), Y.cols());
    for (Eigen::Index k = 0; k < G.size(); ++k) G.data()[k] = RandomVector(1, 1.0, &rng)[0];
    EXPECT_NEAR(ContractJointTorqueRegressorT<double>(model_, friction, q, qd, qdd, G, &d), (G.array() * Y.array()).sum(),
                1e-12 * (G.array().abs() * Y.array().abs()).sum());
  }
  EXPECT_EQ(StandardParameterNames(model_, friction)[static_cast<size_t>(o)], "Fvm1");
}

// A diagonal A: the motor terms act as the joint-side ones Ia·N², Fv·N²,
// Fc·|N| (what ModelWithStandardParameters gives the joints).
TEST_P(JointTorqueRegressorTest, DiagonalActuatorSideEqualsItsJointSideEquivalents) {
  RobotData d(model_);
  const int n = model_.n_dof();
  std::mt19937 rng(45);
  FrictionModel joint;
  joint.viscous = joint.coulomb = joint.rotor_inertia = true;
  FrictionModel actuator = joint;
  const Eigen::VectorXd N = RandomVector(n, 50.0, &rng);
  actuator.actuator_from_joint = N.asDiagonal();
  Eigen::VectorXd pi_motor = StandardParameters(model_, actuator);
  pi_motor.tail(3 * n) = RandomVector(3 * n, 1e-3, &rng).cwiseAbs();
  const RobotModel equivalent = ModelWithStandardParameters(model_, actuator, pi_motor);
  const Eigen::VectorXd pi_joint = StandardParameters(equivalent, joint);
  for (int j = 0; j < n; ++j) {
    EXPECT_NEAR(pi_joint[10 * n + 3 * j + 2], pi_motor[10 * n + 3 * j + 2] * N[j] * N[j], 1e-15 * N[j] * N[j]);
  }
  Eigen::MatrixXd Y_motor, Y_joint;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 2.0, &rng),
                          qdd = RandomVector(n, 5.0, &rng);
    ComputeJointTorqueRegressor(model_, actuator, q, qd, qdd, &d, &Y_motor);
    ComputeJointTorqueRegressor(model_, joint, q, qd, qdd, &d, &Y_joint);
    EXPECT_LT(testing::RelativeError(Y_motor * pi_motor, Y_joint * pi_joint), 1e-12) << "trial " << trial;
  }
}

// coulomb_min_speed: a joint slower than it has a Coulomb column of 0 and
// every other entry of Y as without it; a faster joint keeps sign(qd), or
// tanh(qd/v) with smoothing. The contraction (what the excitation design's
// gradient uses) agrees with the entries.
TEST_P(JointTorqueRegressorTest, CoulombColumnIsZeroBelowTheMinimumSpeed) {
  RobotData d(model_);
  const int n = model_.n_dof(), o = 10 * model_.n_links();
  constexpr double kMinSpeed = 0.05;  // [rad/s]
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int n_slow = 0, n_fast = 0;
  for (const double smoothing : {0.0, 0.02}) {
    FrictionModel without;
    without.viscous = without.coulomb = without.offset = without.rotor_inertia = true;
    without.coulomb_smoothing = smoothing;
    FrictionModel with = without;
    with.coulomb_min_speed = kMinSpeed;
    Eigen::MatrixXd Y_without, Y_with;
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qdd = RandomVector(n, 5.0, &rng);
      // Every other joint below the speed (down to 0 and −0), the rest above.
      Eigen::VectorXd qd(n);
      for (int j = 0; j < n; ++j) {
        qd[j] = (j + trial) % 2 == 0 ? 0.999 * kMinSpeed * u(rng) : std::copysign(kMinSpeed + 2.0 * std::abs(u(rng)), u(rng));
      }
      if (trial == 0) qd[0] = 0.0;
      if (trial == 2) qd[0] = -0.0;
      ComputeJointTorqueRegressor(model_, without, q, qd, qdd, &d, &Y_without);
      ComputeJointTorqueRegressor(model_, with, q, qd, qdd, &d, &Y_with);
      Eigen::MatrixXd expected = Y_without;
      for (int j = 0; j < n; ++j) {
        const double column = smoothing > 0.0 ? std::tanh(qd[j] / smoothing) : double((qd[j] > 0.0) - (qd[j] < 0.0));
        ASSERT_EQ(Y_without(j, o + 4 * j + 1), column) << "joint " << j + 1;
        if (std::abs(qd[j]) < kMinSpeed) {
          expected(j, o + 4 * j + 1) = 0.0;
          ++n_slow;
        } else {
          ++n_fast;
        }
      }
      EXPECT_EQ(Y_with, expected) << "trial " << trial << ", smoothing " << smoothing;
      Eigen::MatrixXd G(Y_with.rows(), Y_with.cols());
      for (Eigen::Index k = 0; k < G.size(); ++k) G.data()[k] = u(rng);
      EXPECT_NEAR(ContractJointTorqueRegressorT<double>(model_, with, q, qd, qdd, G, &d),
                  (G.array() * Y_with.array()).sum(), 1e-12 * (G.array().abs() * Y_with.array().abs()).sum());
    }
  }
  EXPECT_GT(n_slow, 10);
  EXPECT_GT(n_fast, 10);
}

// On the actuator side the speed is the motor's, θ̇m_k = A_k·q̇: a slow motor's
// Coulomb column is 0 in every joint's row, whatever the joints' own speeds.
TEST_P(JointTorqueRegressorTest, ActuatorSideCoulombColumnIsZeroBelowTheMotorsMinimumSpeed) {
  RobotData d(model_);
  const int n = model_.n_dof(), o = 10 * model_.n_links();
  if (n < 2) GTEST_SKIP() << "needs two joints for a coupled motor";
  std::mt19937 rng(47);
  FrictionModel without;
  without.viscous = without.coulomb = without.offset = without.rotor_inertia = true;
  without.actuator_from_joint = Eigen::MatrixXd::Identity(n, n) * 30.0;
  without.actuator_from_joint(n - 1, n - 2) = 30.0;  // the last motor turns with the joint before
  FrictionModel with = without;
  with.coulomb_min_speed = 0.5;  // [rad/s] of the motor
  // The last motor nearly still (its joints turning against each other at
  // 1 rad/s), the others at 30 rad/s and more.
  Eigen::VectorXd theta_d = RandomVector(n, 1.0, &rng);
  for (int k = 0; k < n; ++k) theta_d[k] = std::copysign(30.0 + 10.0 * std::abs(theta_d[k]), theta_d[k]);
  theta_d[n - 1] = 0.2;
  const Eigen::VectorXd qd = without.actuator_from_joint.partialPivLu().solve(theta_d);
  ASSERT_GT(std::abs(qd[n - 1]), 0.5);
  const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qdd = RandomVector(n, 5.0, &rng);
  Eigen::MatrixXd Y_without, Y_with;
  ComputeJointTorqueRegressor(model_, without, q, qd, qdd, &d, &Y_without);
  ComputeJointTorqueRegressor(model_, with, q, qd, qdd, &d, &Y_with);
  Eigen::MatrixXd expected = Y_without;
  const int fc_last = o + 4 * (n - 1) + 1;
  EXPECT_EQ(Y_without.col(fc_last).cwiseAbs().maxCoeff(), 30.0);
  expected.col(fc_last).setZero();
  EXPECT_EQ(Y_with, expected);
}

// Negative, NaN or infinite speeds are refused, naming the field; the base
// parameters (every identification computes them) refuse them too.
TEST(FrictionModelTest, CoulombSpeedsMustBeFiniteAndNonNegative) {
  FrictionModel f;
  f.coulomb = true;
  std::string why;
  EXPECT_TRUE(f.IsValid(&why));
  f.coulomb_min_speed = -0.01;
  EXPECT_FALSE(f.IsValid(&why));
  EXPECT_EQ(why, "coulomb_min_speed: expected >= 0 rad/s, got -0.01");
  EXPECT_THROW(ComputeBaseParameters(MakePaper6r(), f), std::invalid_argument);
  f.coulomb_min_speed = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(f.IsValid(&why));
  EXPECT_EQ(why, "coulomb_min_speed: expected >= 0 rad/s, got nan");
  f.coulomb_min_speed = 0.02;
  f.coulomb_smoothing = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(f.IsValid(&why));
  EXPECT_EQ(why, "coulomb_smoothing: expected >= 0 rad/s, got inf");
  f.coulomb_smoothing = 0.01;  // both together: tanh above the speed, 0 below
  EXPECT_TRUE(f.IsValid(nullptr));
}

INSTANTIATE_TEST_SUITE_P(Robots, JointTorqueRegressorTest, ::testing::Range(0, testing::kNumTestRobots),
                         testing::TestRobotName);

}  // namespace
}  // namespace idbench
