#include "idbench/engine/simulation.h"

#include <gtest/gtest.h>

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
    // The first two hinges follow ½ a t² to the discretisation error of the
    // tracked semi-implicit Euler steps (O(dt·qd)/ω, here below 0.01°).
    EXPECT_LT((step.q.head(2) - ref.q.head(2)).cwiseAbs().maxCoeff(), 1.7e-4);
    // The locked hinges do not move at all.
    EXPECT_LT(step.q.tail(4).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(step.qd.tail(4).cwiseAbs().maxCoeff(), 1e-12);
  }
  // The recorded acceleration is the one integrated: qd_{n+1} = qd_n + dt·qdd_n.
  for (size_t n = 0; n + 1 < log.steps.size(); ++n) {
    const Eigen::VectorXd qd_next = log.steps[n].qd + log.dt * log.steps[n].qdd;
    EXPECT_LT((qd_next - log.steps[n + 1].qd).cwiseAbs().maxCoeff(), 1e-14);
  }
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
