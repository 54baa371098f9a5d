#include "idbench/excitation/design_problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "excitation/design_test_util.h"

#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {

// The PUMA 560, its joint-torque regressor (viscous and Coulomb friction) and
// the limits the PUMA tests design within (1.5 rad/s, 4 rad/s²). Not copied:
// the regressor keeps the model.
struct Puma {
  Puma() = default;
  Puma(const Puma&) = delete;
  Puma& operator=(const Puma&) = delete;

  const RobotModel model = MakePuma560();
  const DesignRegressor regressor = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  const std::vector<JointLimits> limits = testing::DesignLimits(model, 1.5, 4.0);
};

DesignOptions SmallOptions(bool rest_to_rest) {
  DesignOptions o;
  o.harmonics = 2;
  o.f0 = 0.25;
  o.samples = 40;
  o.rest_to_rest = rest_to_rest;
  return o;
}

// The criterion's exact gradient in θ (dσ_i = u_iᵀ dW v_i, dual-number state
// derivatives, Fourier chain rule) against central differences.
void ExpectGradientMatchesFiniteDifferences(const DesignProblem& problem, unsigned seed) {
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(seed, &ws);
  Eigen::VectorXd grad(problem.n_unknowns()), fd(problem.n_unknowns());
  const double c = problem.Criterion(theta.data(), grad.data(), &ws);
  ASSERT_LT(c, DesignProblem::kRankDeficientValue);
  for (int i = 0; i < problem.n_unknowns(); ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(theta[i]));
    Eigen::VectorXd tp = theta, tm = theta;
    tp[i] += h;
    tm[i] -= h;
    fd[i] = (problem.Criterion(tp.data(), nullptr, &ws) - problem.Criterion(tm.data(), nullptr, &ws)) / (2 * h);
  }
  EXPECT_LT((grad - fd).norm(), 1e-5 * fd.norm()) << "analytic " << grad.transpose() << "\nfd " << fd.transpose();
}

TEST(DesignProblemTest, JointTorqueGradientMatchesFiniteDifferences) {
  const Puma puma;
  const DesignRegressor& r = puma.regressor;
  for (DesignCriterion c : {DesignCriterion::kLogCond, DesignCriterion::kLogCondNormalised,
                            DesignCriterion::kLogDet, DesignCriterion::kHybrid}) {
    DesignOptions o = SmallOptions(false);
    o.criterion = c;
    SCOPED_TRACE(DesignCriterionName(c));
    ExpectGradientMatchesFiniteDifferences(DesignProblem(r, puma.limits, o), 3);
  }
}

TEST(DesignProblemTest, PerBodyRestToRestGradientMatchesFiniteDifferences) {
  const RobotModel model = MakePaper6r();
  const DesignRegressor r = DesignRegressor::PerBody(model);
  DesignOptions o = SmallOptions(true);
  o.criterion = DesignCriterion::kLogCondNormalised;
  ExpectGradientMatchesFiniteDifferences(DesignProblem(r, testing::DesignLimits(model, 1.0, 3.0), o), 4);
}

// The linear rows are the trajectory's own q, qd, qdd at the grid times (an
// independent evaluation through FourierSeriesTrajectory), normalised.
TEST(DesignProblemTest, LinearRowsAreTheMotionAgainstItsLimits) {
  const Puma puma;
  const DesignRegressor& r = puma.regressor;
  DesignOptions o = SmallOptions(true);
  const std::vector<JointLimits>& limits = puma.limits;
  const DesignProblem problem(r, limits, o);
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(7, &ws);
  const FourierSeriesTrajectory trajectory = problem.Trajectory(theta);
  const std::vector<double>& times = problem.row_times();
  ASSERT_EQ(times.size(), 50u);  // 25 per period of the top harmonic: 0.5 Hz over 4 s (40 samples are fewer)
  ASSERT_EQ(problem.rows().size(), times.size() * 6 * 6);
  double worst = -1e9;
  size_t i = 0;
  for (int j = 0; j < 6; ++j) {
    const JointLimits& l = limits[static_cast<size_t>(j)];
    const double range = l.q_max - l.q_min;
    for (double t : times) {
      const JointState x = trajectory.At(t);
      const double expected[6] = {(x.q[j] - (l.q_max - o.margin * range)) / range,
                                  (-x.q[j] + (l.q_min + o.margin * range)) / range,
                                  x.qd[j] / l.qd_max - (1 - o.margin),
                                  -x.qd[j] / l.qd_max - (1 - o.margin),
                                  x.qdd[j] / l.qdd_max - (1 - o.margin),
                                  -x.qdd[j] / l.qdd_max - (1 - o.margin)};
      for (double e : expected) {
        EXPECT_NEAR(problem.LinearValue(problem.rows()[i++], theta.data()), e, 1e-12);
        worst = std::max(worst, e);
      }
    }
  }
  // The start point is feasible with its tightest limit at 90 %.
  EXPECT_LE(problem.MaxLinearViolation(theta.data()), 1e-12);
  EXPECT_GT(worst, -0.2);
}

// Torque constraints: value against the inverse dynamics at the grid, gradient
// against central differences.
TEST(DesignProblemTest, TorqueConstraintValueAndGradient) {
  const Puma puma;
  const RobotModel& model = puma.model;
  const DesignRegressor& r = puma.regressor;
  std::vector<JointLimits> limits = puma.limits;
  limits[1].tau_max = 80.0;
  limits[2].tau_max = 40.0;
  DesignOptions o = SmallOptions(false);
  o.clearance = -1.0;  // torque only here
  const DesignProblem problem(r, limits, o);
  ASSERT_EQ(problem.n_torque_constraints(), 2);
  ASSERT_EQ(problem.n_nonlinear_constraints(), 2);
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(5, &ws);
  double value[2], grad[2 * 200];
  ASSERT_LE(problem.n_unknowns(), 200);
  problem.NonlinearConstraints(theta.data(), value, grad, &ws);
  for (int m = 0; m < 2; ++m) {
    for (int i = 0; i < problem.n_unknowns(); ++i) {
      const double h = 1e-6;
      Eigen::VectorXd tp = theta, tm = theta;
      tp[i] += h;
      tm[i] -= h;
      double vp[2], vm[2];
      problem.NonlinearConstraints(tp.data(), vp, nullptr, &ws);
      problem.NonlinearConstraints(tm.data(), vm, nullptr, &ws);
      EXPECT_NEAR(grad[m * problem.n_unknowns() + i], (vp[m] - vm[m]) / (2 * h), 1e-6) << m << " " << i;
    }
  }
  const FeasibilityCheck check = CheckTrajectoryLimits(model, limits, problem.Trajectory(theta), 1.0 / 0.1);
  for (const ConstraintMargin& c : check.margins) {
    if (c.quantity == "tau" && c.joint == 1) {
      EXPECT_NEAR(1.0 - c.value / 80.0 - 0.02, -value[0], 1e-9);
    }
  }
}

// Clearance constraints: one per pair, the worst grid distance against the
// minimum, with the gradient at that sample against central differences.
TEST(DesignProblemTest, ClearanceConstraintValueAndGradient) {
  const Puma puma;
  const RobotModel& model = puma.model;
  const DesignRegressor& r = puma.regressor;
  DesignOptions o = SmallOptions(false);
  o.clearance = 0.05;
  const DesignProblem problem(r, puma.limits, o);
  ASSERT_NE(problem.clearance(), nullptr);
  const int m = problem.n_nonlinear_constraints();
  ASSERT_EQ(m, static_cast<int>(problem.clearance()->pairs().size()));
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(9, &ws);
  std::vector<double> value(static_cast<size_t>(m)), grad(static_cast<size_t>(m * problem.n_unknowns()));
  problem.NonlinearConstraints(theta.data(), value.data(), grad.data(), &ws);
  // Values: the 1 kHz check over the same instants agrees.
  const FeasibilityCheck check =
      CheckTrajectoryLimits(model, puma.limits, problem.Trajectory(theta), 10.0, problem.clearance());
  int compared = 0;
  for (const ConstraintMargin& c : check.margins) {
    if (c.quantity != "clearance") continue;
    EXPECT_NEAR((0.05 + 0.001 - c.value) / 0.1, value[static_cast<size_t>(c.joint)], 1e-9) << c.pair;
    ++compared;
  }
  EXPECT_EQ(compared, m);
  const double h = 1e-5;
  for (int i = 0; i < problem.n_unknowns(); ++i) {
    Eigen::VectorXd tp = theta, tm = theta;
    tp[i] += h;
    tm[i] -= h;
    std::vector<double> vp(static_cast<size_t>(m)), vm(static_cast<size_t>(m));
    problem.NonlinearConstraints(tp.data(), vp.data(), nullptr, &ws);
    problem.NonlinearConstraints(tm.data(), vm.data(), nullptr, &ws);
    for (int c = 0; c < m; ++c) {
      EXPECT_NEAR(grad[static_cast<size_t>(c * problem.n_unknowns() + i)], (vp[c] - vm[c]) / (2 * h), 2e-3)
          << problem.clearance()->pairs()[static_cast<size_t>(c)].Name(model) << " unknown " << i;
    }
  }
}

// The pruned minimum over the clearance grid (capsule and reach bounds)
// equals the brute force: every pair at every grid instant by GJK, for
// starts and for motions grown well beyond them.
TEST(DesignProblemTest, ClearanceMinimumEqualsTheBruteForceOverTheGrid) {
  const Puma puma;
  const RobotModel& model = puma.model;
  const DesignRegressor& r = puma.regressor;
  DesignOptions o = SmallOptions(false);
  o.clearance = 0.05;
  const DesignProblem problem(r, puma.limits, o);
  const ClearanceModel& clearance = *problem.clearance();
  const size_t m = clearance.pairs().size();
  DesignProblem::Workspace ws(problem);
  // The slack: min(1 mm, the distance at the home pose less the minimum).
  KinematicsData<double> k(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  std::vector<Clearance> d;
  ComputeKinematicsT<double>(model, problem.home(), zero, zero, &k);
  clearance.Compute(k, &d);
  std::vector<double> slack(m);
  for (size_t i = 0; i < m; ++i) slack[i] = std::clamp(d[i].distance - clearance.pairs()[i].minimum, 0.0, 1e-3);
  int compared = 0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    for (double grow : {1.0, 4.0}) {
      Eigen::VectorXd theta = problem.StartPoint(seed, &ws);
      for (int j = 0; j < 6; ++j) theta.segment(j * problem.block() + 1, 2 * problem.harmonics()) *= grow;
      std::vector<double> value(m);
      problem.NonlinearConstraints(theta.data(), value.data(), nullptr, &ws);
      const FourierSeriesTrajectory trajectory = problem.Trajectory(theta);
      std::vector<double> worst(m, std::numeric_limits<double>::infinity());
      const size_t stride = static_cast<size_t>((o.samples + 99) / 100);
      JointState x(6);
      for (size_t s = 0; s < problem.times().size(); s += stride) {
        trajectory.Evaluate(problem.times()[s], &x);
        ComputeKinematicsT<double>(model, x.q, zero, zero, &k);
        clearance.Compute(k, &d);
        for (size_t i = 0; i < m; ++i) worst[i] = std::min(worst[i], d[i].distance);
      }
      for (size_t i = 0; i < m; ++i) {
        EXPECT_NEAR(value[i], (clearance.pairs()[i].minimum + slack[i] - worst[i]) / 0.1, 1e-6)
            << clearance.pairs()[i].Name(model) << " seed " << seed << " grown " << grow;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, static_cast<int>(6 * m));
}

}  // namespace
}  // namespace idbench
