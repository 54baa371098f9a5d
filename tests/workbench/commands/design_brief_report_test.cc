// DesignCommandReport's status and BriefReport() (issue 25): a design on the
// PUMA 560 within loose limits is feasible; a shoulder torque limit just
// above the gravity torque at the given home leaves no start feasible (the
// search ran); a home outside the paper robot's range admits no motion
// (nothing searched); a joint held still by its limits leaves parameters
// unexcited. The one-line report carries the run's own numbers: the
// condition numbers of W before and after (Identifiability, computed apart
// from the criterion), the evaluations and the wall time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "excitation/design_test_util.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/workbench/commands/design_command.h"
#include "workbench/commands/quick_design_options.h"
#include "workbench/printf_test_util.h"

namespace idbench {
namespace {

using testing::Printf;
using testing::QuickDesignOptions;

// "; 40 evaluations in 0.12 s": the run's count and time as the report rounds them.
std::string EvaluationsAndTime(const DesignResult& r) {
  return "; " + std::to_string(r.evaluations) + " evaluations in " + Printf("%.2f", r.wall_seconds) + " s";
}

TEST(DesignBriefReportTest, AFeasibleDesignReportsItsCriterionVerdictAndTime) {
  const RobotModel model = MakePuma560();
  DesignCommandOptions options = QuickDesignOptions("puma560");
  options.design.max_evaluations = 40;
  const DesignCommandReport report = RunDesign(model, options, testing::DesignLimits(model, 1.5, 4.0), {});
  ASSERT_EQ(report.status(), DesignStatus::kFeasible);
  const DesignResult& r = report.result;
  ASSERT_TRUE(r.usable()) << r.Rejection();
  ASSERT_GT(r.evaluations, 0);
  EXPECT_LT(r.final.cond, r.initial.cond);
  EXPECT_EQ(report.BriefReport(), "design feasible: cond " + Printf("%.4g", r.initial.cond) + " -> cond " +
                                      Printf("%.4g", r.final.cond) + ", feasible at 1000 Hz, usable" +
                                      EvaluationsAndTime(r));
}

TEST(DesignBriefReportTest, NoFeasibleStartReportsTheSearchThatFailed) {
  const RobotModel model = MakePuma560();
  DesignCommandOptions options = QuickDesignOptions("puma560");
  options.design.max_evaluations = 10;
  options.home = {0.0, 0.6, -0.4, 0.0, 0.5, 0.0};
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  RobotData data(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  const Eigen::VectorXd home = Eigen::Map<const Eigen::VectorXd>(options.home.data(), 6);
  limits[1].tau_max = std::abs(InverseDynamics(model, home, zero, zero, &data)[1]) / 0.99;  // the 2 % margin cuts below gravity
  const DesignCommandReport report = RunDesign(model, options, limits, {});
  ASSERT_EQ(report.status(), DesignStatus::kInfeasible) << report.BriefReport();
  const DesignResult& r = report.result;
  EXPECT_FALSE(r.usable());
  EXPECT_FALSE(r.infeasibility.before_search);
  EXPECT_EQ(r.check.rate_hz, 1000.0);  // where the least-violating start ended, against the limits untightened
  EXPECT_EQ(r.starts.size(), 2u);
  EXPECT_GT(r.evaluations, 0);  // the search ran
  EXPECT_EQ(report.BriefReport(),
            "design infeasible: no feasible design: no start met the limits (tightened by the margin 0.02) and the "
            "clearance on the sample grid" + EvaluationsAndTime(r));
}

// Joint 6 held still by its limits: the design meets every limit but leaves
// its parameters unexcited; the report says so as a status (the front ends
// then write nothing), naming the rank of W and the parameters.
TEST(DesignBriefReportTest, AJointHeldStillLeavesParametersUnexcited) {
  const RobotModel model = MakePuma560();
  DesignCommandOptions options = QuickDesignOptions("puma560");
  options.design.starts = 1;
  options.design.max_evaluations = 5;
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  limits[5].qd_max = limits[5].qdd_max = 1e-12;
  const DesignCommandReport report = RunDesign(model, options, limits, {});
  ASSERT_EQ(report.status(), DesignStatus::kNotExcited) << report.BriefReport();
  const DesignResult& r = report.result;
  EXPECT_FALSE(r.usable());
  EXPECT_TRUE(r.check.feasible()) << r.check.Explain();
  EXPECT_GT(r.evaluations, 0);  // the search ran
  // Viscous and Coulomb friction on 6 joints with the inertial parameters: the
  // regressor's columns, of which joint 6's viscous friction is not excited.
  const int n = static_cast<int>(report.parameter_names.size());
  ASSERT_LT(r.final.rank, n);
  const std::string head = "no design within these limits excites every parameter (rank " +
                           std::to_string(r.final.rank) + " of " + std::to_string(n) +
                           "); check the limits of the joints involved";
  EXPECT_EQ(r.infeasibility.explanation.rfind(head + ":\n", 0), 0u) << r.infeasibility.explanation;
  EXPECT_NE(r.infeasibility.explanation.find("\n  column of Fv6 is zero: the data do not excite it"),
            std::string::npos)
      << r.infeasibility.explanation;
  EXPECT_EQ(report.BriefReport(), "design not_excited: " + head + EvaluationsAndTime(r));
}

TEST(DesignBriefReportTest, AHomeOutsideTheRangeAdmitsNoMotion) {
  const RobotModel model = MakePaper6r();
  DesignCommandOptions options = QuickDesignOptions("paper6r");
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  limits[0].q_min = -2.5, limits[0].q_max = 2.5;
  options.home = {2.5, 0.0, 0.0, 0.0, 0.0, 0.0};  // on the range, outside it tightened by the margin
  const DesignCommandReport report = RunDesign(model, options, limits, {});
  ASSERT_EQ(report.status(), DesignStatus::kNoMotionPossible) << report.BriefReport();
  const DesignResult& r = report.result;
  EXPECT_TRUE(r.infeasibility.before_search);
  EXPECT_EQ(r.evaluations, 0);  // nothing searched
  EXPECT_TRUE(r.starts.empty());
  EXPECT_EQ(report.BriefReport(),
            "design no_motion_possible: no motion is possible with these settings: the `home` pose 2.5,0,0,0,0,0 "
            "violates the limits (ranges tightened by the margin 0.02) or the clearance held still" +
                EvaluationsAndTime(r));
}

}  // namespace
}  // namespace idbench
