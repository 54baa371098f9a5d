#include "idbench/excitation/excitation_design.h"

#include <gtest/gtest.h>

#include "excitation/design_test_util.h"

#include <numbers>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

// The check finds a violation where it analytically is: q = sin(t) has its
// velocity peak |qd| = 1 at t = 0 (and 2π).
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
