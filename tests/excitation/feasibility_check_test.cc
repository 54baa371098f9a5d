#include "idbench/excitation/excitation_design.h"

#include <gtest/gtest.h>

#include "excitation/design_test_util.h"

#include <numbers>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

// The check finds a violation where it analytically is: q = sin(t) has its
// velocity peak |qd| = 1 at t = 0 (and 2π).
// A motor's velocity θ̇m = A·q̇ through a TX40-like wrist (motor 6 turns with
// joint 5: θ̇m6 = 32·(q̇5 + q̇6)): q5 = sin t, q6 = sin(t)/2 give θ̇m6 = 48 cos t,
// its peak 48 rad/s at t = 0, while every joint stays within its own limits.
TEST(ExcitationDesignTest, CheckNamesTheMotorAndTheJointsItDrives) {
  const RobotModel model = MakePaper6r();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 1), b = Eigen::MatrixXd::Zero(6, 1);
  a(4, 0) = 1.0;
  a(5, 0) = 0.5;
  const FourierSeriesTrajectory motion(Eigen::VectorXd::Zero(6), a, b, 1.0 / (2 * std::numbers::pi),
                                       2 * std::numbers::pi);
  const std::vector<JointLimits> limits = testing::DesignLimits(model, 2.0, 2.0);
  ActuatorLimits actuators;
  actuators.transmission = Transmission::FromReduction({32, 32, 45, -48, 45, 32});
  actuators.transmission.actuator_from_joint(5, 4) = 32;
  actuators.motors.resize(6);
  actuators.motors[5].qd_max = 40.0;
  const FeasibilityCheck check = CheckTrajectoryLimits(model, limits, motion, 1000.0, nullptr, actuators);
  int violations = 0;
  for (const ConstraintMargin& m : check.margins) {
    if (m.margin >= 0.0) continue;
    ++violations;
    EXPECT_EQ(m.motor, 5);
    EXPECT_EQ(m.quantity, "qd");
    EXPECT_NEAR(m.value, 48.0, 1e-12);
    EXPECT_NEAR(m.margin, -8.0, 1e-12);
  }
  EXPECT_EQ(violations, 1);
  EXPECT_NE(check.Explain().find("motor 6 (joints O5, O6) qd: |θ̇m| = 48 rad/s at t = 0 s exceeds the limit 40 rad/s "
                                 "by 8 rad/s"),
            std::string::npos)
      << check.Explain();
  // Advice names the field that holds the limit.
  const std::vector<std::string> advice = RelaxationAdvice(check, DesignOptions{}, false);
  ASSERT_FALSE(advice.empty());
  EXPECT_NE(advice[0].find("actuators[5].qd_max"), std::string::npos) << advice[0];
}

TEST(ExcitationDesignTest, CheckNamesJointTimeAndAmount) {
  const RobotModel model = MakePaper6r();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 1), b = Eigen::MatrixXd::Zero(6, 1);
  a(2, 0) = 1.0;  // joint 3: q = sin(t), qd = cos(t), qdd = −sin(t)
  const FourierSeriesTrajectory motion(Eigen::VectorXd::Zero(6), a, b, 1.0 / (2 * std::numbers::pi),
                                       2 * std::numbers::pi);
  std::vector<JointLimits> limits = testing::DesignLimits(model, 0.9, 2.0);
  const FeasibilityCheck check = CheckTrajectoryLimits(model, limits, motion, 1000.0);
  EXPECT_FALSE(check.feasible());
  int violations = 0;
  for (const ConstraintMargin& m : check.margins) {
    if (m.margin >= 0.0) continue;
    ++violations;
    EXPECT_EQ(m.joint, 2);
    EXPECT_EQ(m.quantity, "qd");
    EXPECT_NEAR(m.value, 1.0, 1e-12);
    EXPECT_NEAR(m.margin, -0.1, 1e-12);
    EXPECT_NEAR(m.time, 0.0, 1e-12);
  }
  EXPECT_EQ(violations, 1);
  EXPECT_NE(check.Explain().find("joint 3 qd: |qd| = 1 rad/s at t = 0 s exceeds the limit 0.9 rad/s by 0.1 rad/s"),
            std::string::npos)
      << check.Explain();
}

}  // namespace
}  // namespace idbench
