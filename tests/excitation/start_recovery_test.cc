// A start's recovery (excitation/src/start_recovery.cc, design_start.cc):
// the feasibility phase, joints held still at the start, and the design on
// the UR10e-like arm with its clearance, where every start must end feasible
// and better than it began.
#include "../../excitation/src/design_start.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "excitation/design_test_util.h"
#include "idbench/engine/urdf.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {

const char* const kUrLike = IDBENCH_SOURCE_DIR "/tests/data/ur10e_like/ur10e_like.urdf";
const char* const kKuka = IDBENCH_SOURCE_DIR "/../shared/data/kuka_lwr4/lwr_description/urdf/kuka_lwr4.urdf";
const char* const kUr10e = IDBENCH_SOURCE_DIR "/../shared/data/robots/ur_e_description/urdf/ur10e.urdf";

// The arm's own ranges and velocity limits, tests/data/ur10e_like/lim_acc.json's accelerations.
std::vector<JointLimits> UrLikeLimits(const RobotModel& model) {
  const double qdd[6] = {3, 3, 5, 5, 5, 5};
  std::vector<JointLimits> limits;
  for (int j = 0; j < 6; ++j) limits.push_back(model.link(j).limits), limits.back().qdd_max = qdd[j];
  return limits;
}

DesignOptions QuickOptions(double clearance) {
  DesignOptions o;
  o.harmonics = 3;
  o.f0 = 0.2;
  o.samples = 60;
  o.clearance = clearance;
  return o;
}

// A start pushed into the floor (the shoulder lowered by 1.4 rad, every
// amplitude trebled) is infeasible on the grid; the feasibility phase ends
// at a point that meets every constraint there and still moves.
TEST(StartRecoveryTest, FeasibilityPhaseTurnsAnInfeasibleStartFeasible) {
  const RobotModel model = LoadUrdfFile(kUrLike).model;
  const DesignRegressor r = DesignRegressor::JointTorque(model, FrictionModel{});
  const std::vector<JointLimits> limits = UrLikeLimits(model);
  const DesignOptions options = QuickOptions(0.01);
  DesignProblem problem(r, limits, options);
  problem.set_home((Eigen::VectorXd(6) << 0, -0.5, 0, 0, 0, 0).finished());
  const DesignControl control;
  internal::StartRun run;
  run.problem = &problem;
  run.options = &options;
  run.control = &control;
  run.ws.emplace(problem);
  Eigen::VectorXd theta = problem.StartPoint(1, &*run.ws);
  ASSERT_TRUE(run.Feasible(theta.data()));
  theta[1 * problem.block()] += 1.4;  // shoulder_lift_joint's q0: the arm down to the floor
  for (int j = 0; j < 6; ++j) theta.segment(j * problem.block() + 1, 2 * problem.harmonics()) *= 3.0;
  const double before = run.Violation(theta.data());
  ASSERT_GT(before, 0.05) << run.WorstConstraint(theta.data());
  Eigen::VectorXd lower, upper;
  problem.Bounds(&lower, &upper);
  const int used = run.Centre(lower, upper, 0.1, 200, &theta);
  EXPECT_LE(used, 200);
  EXPECT_EQ(run.evaluations, used);
  EXPECT_TRUE(run.Feasible(theta.data())) << run.WorstConstraint(theta.data());
  EXPECT_LE(run.Violation(theta.data()), 0.0);
  // What is left is still a motion (the home pose alone would be feasible).
  double amplitude = 0.0;
  for (int j = 0; j < 6; ++j) amplitude += theta.segment(j * problem.block() + 1, 2 * problem.harmonics()).norm();
  EXPECT_GT(amplitude, 0.01);
}

// The KUKA LWR4+ at 0.2 m (../shared/data): at its home q = 0, the arm
// straight up, pairs closer than 0.2 m are held at their distance there,
// which any bend reduces; the start holds those joints still, names them
// with the constraint, and is feasible on the grid.
TEST(StartRecoveryTest, StartHoldsStillTheJointsWhoseMotionBreaksAHeldPair) {
  if (!std::filesystem::exists(kKuka)) GTEST_SKIP() << kKuka << " not found (../shared is not beside the checkout)";
  const RobotModel model = LoadUrdfFile(kKuka).model;
  const DesignRegressor r = DesignRegressor::JointTorque(model, FrictionModel{});
  const DesignProblem problem(r, testing::DesignLimits(model, 1.5, 5.0), QuickOptions(0.2));
  DesignProblem::Workspace ws(problem);
  std::vector<std::string> held;
  const Eigen::VectorXd theta = problem.StartPoint(1, &ws, &held);
  ASSERT_FALSE(held.empty());
  for (const std::string& h : held) EXPECT_NE(h.find("its distance at q = 0"), std::string::npos) << h;
  std::vector<double> values(static_cast<size_t>(problem.n_nonlinear_constraints()));
  problem.NonlinearConstraints(theta.data(), values.data(), nullptr, &ws);
  EXPECT_LE(*std::max_element(values.begin(), values.end()), 0.0);
  EXPECT_LE(problem.MaxLinearViolation(theta.data()), 0.0);
  // The held joints are the still ones: zero amplitude, the others moving.
  int still = 0;
  for (int j = 0; j < model.n_dof(); ++j) still += theta.segment(j * problem.block() + 1, 2 * problem.harmonics()).isZero();
  EXPECT_EQ(still, static_cast<int>(held.size()));
}

// The design on the UR10e-like arm with its default clearance and at 0.2 m
// (pairs held at their q = 0 distance, the case where no start moved): every
// start ends feasible on its grid and below its start point's criterion.
// (The 1 kHz re-check between grid instants is the design's own verdict,
// excitation_design_test; at this coarse grid it can find 0.1 mm short.)
TEST(StartRecoveryTest, EveryStartOnTheUrLikeArmEndsFeasibleAndBetter) {
  const RobotModel model = LoadUrdfFile(kUrLike).model;
  const DesignRegressor r = DesignRegressor::JointTorque(model, FrictionModel{});
  for (double clearance : {0.01, 0.2}) {
    DesignOptions o = QuickOptions(clearance);
    o.starts = 2;
    o.max_evaluations = 120;
    const DesignResult result = DesignExcitation(r, UrLikeLimits(model), o);
    for (size_t s = 0; s < result.starts.size(); ++s) {
      const DesignStartSummary& start = result.starts[s];
      SCOPED_TRACE("clearance " + std::to_string(clearance) + ", start " + std::to_string(s + 1) + ": " + start.outcome);
      EXPECT_TRUE(std::isfinite(start.best_value));
      EXPECT_LT(start.best_value, start.initial_value);
      EXPECT_TRUE(start.progressed);
    }
  }
}

// The vendor UR10e (its own URDF and collision meshes, ../shared/data/robots)
// with the default 1 cm clearance, 4 starts of 150 evaluations: every start
// ends within 2x of the best start's cond (the median of the four within 2x:
// before the second round, starts 1 and 2 ended at 875 and 275 against the
// best 57.3, a median 2.95x the best), and the design holds at 1 kHz, as an
// independent sampler of the clearance sees it (GJK on the same model at
// every millisecond, not the design's own check).
TEST(StartRecoveryTest, MedianStartOnTheVendorUr10eEndsWithinTwiceTheBest) {
  if (!std::filesystem::exists(kUr10e)) GTEST_SKIP() << kUr10e << " not found (../shared is not beside the checkout)";
  const RobotModel model = LoadUrdfFile(kUr10e).model;
  const DesignRegressor r = DesignRegressor::JointTorque(model, FrictionModel{});
  DesignOptions o;  // defaults: H = 5, f0 = 0.1 Hz, 250 samples, 4 starts, 1 cm clearance
  o.max_evaluations = 150;
  o.threads = 1;
  const DesignResult result = DesignExcitation(r, UrLikeLimits(model), o);
  ASSERT_EQ(result.status, DesignStatus::kFeasible) << result.infeasibility.explanation;
  std::vector<double> conds;
  for (const DesignStartSummary& start : result.starts) {
    ASSERT_TRUE(std::isfinite(start.best_value)) << start.outcome;
    conds.push_back(std::exp(start.best_value));  // the criterion is log cond(W)
  }
  std::sort(conds.begin(), conds.end());
  const double median = 0.5 * (conds[1] + conds[2]);
  EXPECT_LE(median, 2.0 * conds[0]) << conds[0] << " " << conds[1] << " " << conds[2] << " " << conds[3];
  EXPECT_NEAR(result.final.cond, conds[0], 1e-4 * conds[0]);
  // The 1 kHz sampler: every pair at every millisecond at least its minimum.
  const ClearanceModel clearance(model, o.clearance);
  const RampedTrajectory motion = result.RobotTrajectory();
  RobotData data(model);
  JointState x(model.n_dof());
  std::vector<Clearance> distances;
  double least_margin = 1e9;
  for (long k = 0; k <= static_cast<long>(motion.duration() * 1000.0); ++k) {
    motion.Evaluate(k / 1000.0, &x);
    ComputeKinematicsT<double>(model, x.q, x.qd, x.qdd, &data);
    clearance.Compute(data, &distances);
    for (size_t i = 0; i < distances.size(); ++i) {
      least_margin = std::min(least_margin, distances[i].distance - clearance.pairs()[i].minimum);
    }
  }
  EXPECT_GE(least_margin, 0.0);
}

}  // namespace
}  // namespace idbench
