#include "idbench/excitation/excitation_design.h"

#include <gtest/gtest.h>

#include "excitation/design_test_util.h"

#include <algorithm>
#include <numbers>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

DesignOptions QuickOptions() {
  DesignOptions o;
  o.harmonics = 3;
  o.f0 = 0.2;
  o.samples = 60;
  o.starts = 3;
  o.max_evaluations = 40;
  return o;
}

TEST(ExcitationDesignTest, ImprovesTheCriterionAndIsFeasibleAtOneKilohertz) {
  const RobotModel model = MakePuma560();
  const DesignRegressor r = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  const DesignResult result = DesignExcitation(r, testing::DesignLimits(model, 1.5, 4.0), QuickOptions());
  EXPECT_LT(result.value, result.initial_value);
  EXPECT_LT(result.final.cond, 0.7 * result.initial.cond);
  EXPECT_NEAR(std::log(result.final.cond), result.value, 1e-9);  // the criterion is log cond(W)
  EXPECT_TRUE(result.check.feasible()) << result.check.Explain();
  EXPECT_EQ(result.check.rate_hz, 1000.0);
  // q_min, q_max, qd, qdd per joint (no torque limits), and every clearance pair.
  EXPECT_EQ(result.check.margins.size(), 6u * 4u + ClearanceModel(model, 0.01).pairs().size());
  EXPECT_EQ(result.starts.size(), 3u);
}

// Same seed: the same design, whatever the number of threads.
TEST(ExcitationDesignTest, DeterministicForASeedAndAnyThreadCount) {
  const RobotModel model = MakePuma560();
  const DesignRegressor r = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  DesignOptions o = QuickOptions();
  o.threads = 1;
  const DesignResult one = DesignExcitation(r, testing::DesignLimits(model, 1.5, 4.0), o);
  o.threads = 2;
  const DesignResult two = DesignExcitation(r, testing::DesignLimits(model, 1.5, 4.0), o);
  EXPECT_EQ(one.value, two.value);
  EXPECT_EQ(one.trajectory.a(), two.trajectory.a());
  EXPECT_EQ(one.trajectory.b(), two.trajectory.b());
  EXPECT_EQ(one.trajectory.q0(), two.trajectory.q0());
  o.seed = 100;  // starts 100..102 (seed 2 would share starts 2 and 3 with seed 1)
  EXPECT_NE(DesignExcitation(r, testing::DesignLimits(model, 1.5, 4.0), o).value, one.value);
}

TEST(ExcitationDesignTest, UnboundedOrInconsistentLimitsAreNamed) {
  const RobotModel model = MakePaper6r();
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.0, 2.0);
  limits[3].qd_max = std::numeric_limits<double>::infinity();
  try {
    CheckDesignLimits(model, limits);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint 4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("qd_max"), std::string::npos) << e.what();
  }
  limits = testing::DesignLimits(model, 1.0, 2.0);
  limits[0].qdd_max = 0.0;
  EXPECT_THROW(CheckDesignLimits(model, limits), std::invalid_argument);
  DesignOptions o;
  o.harmonics = 0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("harmonics: must be in 1.."), std::string::npos);
  o = DesignOptions{};
  o.samples = 20;  // 8 per period of the 0.5 Hz top harmonic over 10 s needs 40
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("samples: must be at least 40"), std::string::npos) << why;
}

// paper6r, per-body model. The normalised cond of the paper's two-hinge
// motion is already 2.2 (each body's Euler block alone 1.9, as `idbench run`
// reports) and cannot fall below 1, so it is no measure of the noise
// sensitivity; the D-optimal design raises σ_min(W) and lowers cond(W) well
// beyond the paper motion's (compare's Monte-Carlo shows the error falling).
TEST(ExcitationDesignTest, PerBodyDesignBeatsThePaperMotion) {
  const RobotModel model = MakePaper6r();
  const DesignRegressor r = DesignRegressor::PerBody(model);
  DesignOptions o = QuickOptions();
  o.criterion = DesignCriterion::kLogDet;
  const DesignResult design = DesignExcitation(r, testing::DesignLimits(model, 1.0, 3.0), o);
  const auto paper = MakePaperMotion(6, 30.0 * std::numbers::pi / 180.0, 2.0);
  std::vector<double> times;
  for (int k = 0; k < 60; ++k) times.push_back(k * 2.0 / 60);
  const Identifiability paper_id = ComputeIdentifiability(r.Stack(*paper, times));
  EXPECT_TRUE(design.check.feasible()) << design.check.Explain();
  EXPECT_NEAR(paper_id.cond_normalised, 2.2, 0.1);
  EXPECT_GT(design.final.sigma_min, 3.0 * paper_id.sigma_min);
  EXPECT_LT(design.final.cond, 0.5 * paper_id.cond);
  EXPECT_NEAR(-design.final.log_det / r.n_parameters(), design.value, 1e-9);
}

// A joint that may barely move leaves its parameters unexcited: the design
// says which ones instead of reporting cond = inf, as a status (kNotExcited)
// whose explanation names the rank and the parameters, and whose motion's
// regressor columns of joint 6's viscous friction are indeed zero.
TEST(ExcitationDesignTest, UnexcitableParametersAreNamed) {
  const RobotModel model = MakePuma560();
  const DesignRegressor r = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  limits[5].qd_max = 1e-12;  // joint 6 held still: its viscous friction and link 6's inertia about its axis
  limits[5].qdd_max = 1e-12;
  DesignOptions o = QuickOptions();
  o.starts = 1;
  o.max_evaluations = 5;
  const DesignResult design = DesignExcitation(r, limits, o);
  ASSERT_EQ(design.status, DesignStatus::kNotExcited);
  EXPECT_FALSE(design.usable());
  EXPECT_FALSE(design.infeasibility.before_search);
  EXPECT_TRUE(design.infeasibility.advice.empty());
  EXPECT_TRUE(design.check.feasible()) << design.check.Explain();  // a motion within the limits
  EXPECT_EQ(design.infeasibility.check.margins.size(), design.check.margins.size());
  // The rank of the design's own regressor, recomputed here.
  const Eigen::MatrixXd W = r.Stack(design.trajectory, DesignSampleTimes(o));
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  const int rank = static_cast<int>((svd.singularValues().array() > 1e-9 * svd.singularValues()[0]).count());
  EXPECT_EQ(design.final.rank, rank);
  ASSERT_LT(rank, r.n_parameters());
  const std::string& what = design.infeasibility.explanation;
  const std::string head = "no design within these limits excites every parameter (rank " + std::to_string(rank) +
                           " of " + std::to_string(r.n_parameters()) + "); check the limits of the joints involved:";
  EXPECT_EQ(what.rfind(head, 0), 0u) << what;
  EXPECT_EQ(design.Rejection(), head.substr(0, head.size() - 1));  // the first line without its ':'
  // Fv6 is named, and its column of W, joint 6's velocity qd6 on its rows, is
  // within the limit qd_max = 1e-12 rad/s: joint 6 does not move.
  EXPECT_NE(what.find("\n  column of Fv6 is zero"), std::string::npos) << what;
  const std::vector<std::string>& names = r.parameter_names();
  const auto fv6 = std::find(names.begin(), names.end(), "Fv6");
  ASSERT_NE(fv6, names.end());
  EXPECT_LE(W.col(fv6 - names.begin()).cwiseAbs().maxCoeff(), limits[5].qd_max);
}

// The re-check covers the ramps from and to the home: too short a ramp
// exceeds qdd_max during it (the check's worst qdd is the ramped motion's,
// found again here on the same 1 kHz grid) and the advice names --ramp; a
// long one keeps the design feasible. The motion itself is the same.
TEST(ExcitationDesignTest, RecheckCoversTheRamps) {
  const RobotModel model = MakePuma560();
  const DesignRegressor r = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  const std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  DesignOptions o = QuickOptions();
  o.ramp_seconds = 0.05;
  const DesignResult sharp = DesignExcitation(r, limits, o);
  const RampedTrajectory robot = sharp.RobotTrajectory();
  EXPECT_DOUBLE_EQ(robot.duration(), 5.0 + 0.1);
  EXPECT_EQ(robot.home(), sharp.home);
  ASSERT_FALSE(sharp.check.feasible());
  Eigen::VectorXd qdd_peak = Eigen::VectorXd::Zero(6);
  for (int k = 0; k <= 5100; ++k) qdd_peak = qdd_peak.cwiseMax(robot.At(k / 1000.0).qdd.cwiseAbs());
  int violated = 0;
  for (const ConstraintMargin& m : sharp.check.margins) {
    if (m.quantity != "qdd") continue;
    EXPECT_NEAR(m.value, qdd_peak[m.joint], 1e-9 * qdd_peak[m.joint]) << "joint " << m.joint + 1;
    if (m.margin < 0.0) {
      ++violated;
      EXPECT_TRUE(m.time < 0.05 || m.time > 5.05) << "joint " << m.joint + 1 << " at " << m.time;
    }
  }
  EXPECT_GT(violated, 0);
  const std::vector<std::string> advice = RelaxationAdvice(sharp.check, o, false);
  ASSERT_FALSE(advice.empty());
  EXPECT_EQ(advice[0].rfind("ramp_seconds (now 0.05 s)", 0), 0u) << advice[0];

  o.ramp_seconds = 12.0;
  const DesignResult smooth = DesignExcitation(r, limits, o);
  EXPECT_TRUE(smooth.check.feasible()) << smooth.check.Explain();
  EXPECT_EQ(smooth.trajectory.a(), sharp.trajectory.a());  // the ramps do not change the search
}

// A home whose gravity torque on joint 2 is 99 % of its limit passes the
// check held still (the limit itself), but the search tightens torque limits
// by the 2 % margin, so no start can meet them: the search runs and fails
// (after the search), the 1 kHz check of where it ended, and --margin advised.
TEST(ExcitationDesignTest, NoFeasibleStartIsExplainedAfterTheSearch) {
  const RobotModel model = MakePuma560();
  const DesignRegressor r = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
  DesignOptions o = QuickOptions();
  o.starts = 2;
  o.max_evaluations = 10;
  o.home = (Eigen::VectorXd(6) << 0.0, 0.6, -0.4, 0.0, 0.5, 0.0).finished();
  RobotData data(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  const double tau_gravity = std::abs(InverseDynamics(model, o.home, zero, zero, &data)[1]);
  ASSERT_GT(tau_gravity, 10.0);  // the shoulder holds the arm out
  limits[1].tau_max = tau_gravity / 0.99;
  const DesignResult result = DesignExcitation(r, limits, o);
  ASSERT_EQ(result.status, DesignStatus::kInfeasible);
  const DesignInfeasibility& e = result.infeasibility;
  EXPECT_FALSE(e.before_search) << e.explanation;
  EXPECT_NE(e.explanation.find("no feasible design"), std::string::npos) << e.explanation;
  EXPECT_EQ(e.check.rate_hz, 1000.0);
  bool margin = false;
  for (const std::string& a : e.advice) margin |= a.rfind("`margin` (now 0.02)", 0) == 0;
  EXPECT_TRUE(margin) << e.explanation;
  EXPECT_FALSE(result.usable());
  EXPECT_EQ(result.Rejection(),
            "no feasible design: no start met the limits (tightened by the margin 0.02) and the clearance on the "
            "sample grid");
  EXPECT_EQ(result.starts.size(), 2u);
}

}  // namespace
}  // namespace idbench
