#include "idbench/engine/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

TEST(SimulationTest, PaperMotionTracksTheReferenceAndKeepsLockedJointsLocked) {
  const RobotModel model = MakePaper6r();
  const double accel = 30.0 * std::numbers::pi / 180.0;
  const auto reference = MakePaperMotion(6, accel, 2.0);
  const SimulationLog log = Simulate(model, *reference, SimulationOptions{});
  ASSERT_EQ(log.steps.size(), 2000u);
  for (const LogStep& step : log.steps) {
    const JointState ref = reference->At(step.t);
    // The first two hinges follow ½ a t²: the fourth-order step integrates a
    // quadratic exactly, so what is left is Bullet's forward dynamics against
    // our RNEA (~1e-10 relative) and rounding (measured 2.5e-12).
    EXPECT_LT((step.q.head(2) - ref.q.head(2)).cwiseAbs().maxCoeff(), 1e-10);
    // The locked hinges do not move at all.
    EXPECT_LT(step.q.tail(4).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(step.qd.tail(4).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// The log is one motion: its q is the integral of its qd, and qd of its qdd,
// to the integrator's order. Simpson's rule over two steps,
//   x_{n+1} − x_{n−1} = dt/3 · (ẋ_{n−1} + 4 ẋ_n + ẋ_{n+1}) + O(dt⁵ x⁽⁵⁾),
// is a second integrator to check against; its own error on this 0.5–1 Hz
// motion is ~1e-17. What is left is the Runge–Kutta step's local error, which
// the tracking loop sets at ~(ω·dt)⁴·dt·|qd|/120: measured 1.3e-12 rad and
// 3.8e-11 rad/s. Semi-implicit Euler's q, half a step ahead of its qd, missed
// by 3.6e-6 rad and its qd by 1.6e-5 rad/s.
TEST(SimulationTest, LoggedPositionsAreTheIntegralOfTheLoggedVelocities) {
  const RobotModel model = MakePaper6r();
  const auto reference = MakeGeneralMotion(6, 1.0);
  SimulationOptions options;
  options.duration = 1.0;
  const SimulationLog log = Simulate(model, *reference, options);
  const double dt = log.dt;
  double q_error = 0.0, qd_error = 0.0;
  for (size_t n = 1; n + 1 < log.steps.size(); ++n) {
    const LogStep &before = log.steps[n - 1], &now = log.steps[n], &after = log.steps[n + 1];
    const Eigen::VectorXd q_simpson = dt / 3.0 * (before.qd + 4.0 * now.qd + after.qd);
    const Eigen::VectorXd qd_simpson = dt / 3.0 * (before.qdd + 4.0 * now.qdd + after.qdd);
    q_error = std::max(q_error, (after.q - before.q - q_simpson).cwiseAbs().maxCoeff());
    qd_error = std::max(qd_error, (after.qd - before.qd - qd_simpson).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(q_error, 1e-11);
  EXPECT_LT(qd_error, 4e-10);
}

TEST(SimulationTest, RecordedTorquesAreTheInverseDynamicsOfTheRealisedMotion) {
  const RobotModel model = MakePaper6r();
  const auto reference = MakeGeneralMotion(6, 1.0);
  SimulationOptions options;
  options.duration = 0.5;
  const SimulationLog log = Simulate(model, *reference, options);
  RobotData d(model);
  for (size_t n = 0; n < log.steps.size(); n += 50) {
    const LogStep& s = log.steps[n];
    const Eigen::VectorXd tau = InverseDynamics(model, s.q, s.qd, s.qdd, &d);
    EXPECT_LT((tau - s.tau).cwiseAbs().maxCoeff(), 1e-9 * tau.cwiseAbs().maxCoeff()) << "step " << n;
  }
}

TEST(SimulationTest, StepAtFindsTheNearestStep) {
  SimulationLog log;
  log.dt = 1e-3;
  log.steps.resize(2000);
  EXPECT_EQ(log.StepAt(0.3), 300);
  EXPECT_EQ(log.StepAt(1.5), 1500);
  EXPECT_EQ(log.StepAt(1.999), 1999);
  EXPECT_EQ(log.StepAt(2.0), -1);
  EXPECT_EQ(log.StepAt(-0.1), -1);
}

TEST(SimulationTest, RejectsInvalidOptions) {
  const RobotModel model = MakePaper6r();
  const auto reference = MakePaperMotion(6, 0.5, 2.0);
  SimulationOptions options;
  options.dt = 0.0;
  EXPECT_THROW(Simulate(model, *reference, options), std::invalid_argument);
  options = SimulationOptions{};
  options.duration = 3.0;  // longer than the reference
  EXPECT_THROW(Simulate(model, *reference, options), std::invalid_argument);
  const auto wrong_size = MakePaperMotion(5, 0.5, 2.0);
  EXPECT_THROW(Simulate(model, *wrong_size, SimulationOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
