#include "idbench/engine/closed_loop.h"

#include <gtest/gtest.h>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

JointControllerOptions PumaPid() {
  JointControllerOptions pid;
  pid.kp = {400.0};
  pid.kd = {20.0};
  pid.ki = {50.0};
  return pid;
}

// With the plant's own model as feed-forward and no noise, the loop starts on
// the reference and the PID only corrects what the zero-order hold leaves:
// the torque held for 1 ms, the model's at the middle of the hold, while the
// exact one moves (measured 7.7e-8 rad). Coulomb friction steps at each
// velocity reversal, and the held torque cannot follow the step within the
// sample: with puma560's Coulomb friction the error reaches 1.5e-4 rad.
TEST(ClosedLoopTest, PerfectFeedForwardWithoutNoiseTracksTheReference) {
  std::vector<Link> links = MakePuma560().links();
  for (Link& link : links) link.dynamics.coulomb = 0.0;  // viscous friction and rotor inertia stay
  const RobotModel model("puma560", links, MakePuma560().gravity_W());
  const auto reference = MakeGeneralMotion(6, 2.0);
  JointControllerOptions pid = PumaPid();
  pid.model_feedforward = true;
  SimulationOptions options;
  options.duration = 2.0;
  const ClosedLoopLog out = SimulateClosedLoop(model, *reference, options, pid, SensorOptions{});
  ASSERT_EQ(out.log.n_samples(), 2000);
  const double error = (out.log.q - out.q_ref).cwiseAbs().maxCoeff();
  std::printf("tracking error %.3g rad\n", error);
  EXPECT_LT(error, 1e-6);
  EXPECT_GT(error, 0.0);  // the hold does leave something
  const ClosedLoopLog coulomb = SimulateClosedLoop(MakePuma560(), *reference, options, pid, SensorOptions{});
  const double coulomb_error = (coulomb.log.q - coulomb.q_ref).cwiseAbs().maxCoeff();
  std::printf("with Coulomb friction %.3g rad\n", coulomb_error);
  EXPECT_LT(coulomb_error, 1e-3);
}

// The logged torque is the applied one: the inverse dynamics of the logged
// q, qd, qdd plus the joints' friction and rotor terms, which Bullet does not
// model and the loop adds against the torque (rounding of Bullet's
// acceleration: measured 1.3e-13 of the largest torque).
TEST(ClosedLoopTest, LoggedTorqueIsTheInverseDynamicsOfTheLoggedMotion) {
  const RobotModel model = MakePuma560();
  const auto reference = MakeGeneralMotion(6, 1.0);
  SimulationOptions options;
  options.duration = 1.0;
  const ClosedLoopLog out = SimulateClosedLoop(model, *reference, options, PumaPid(), SensorOptions{});
  RobotData data(model);
  double worst = 0.0;
  for (int s = 0; s < out.log.n_samples(); ++s) {
    const Eigen::VectorXd q = out.log.q.row(s).transpose(), qd = out.log.qd.row(s).transpose(),
                          qdd = out.log.qdd.row(s).transpose(), tau = out.log.tau.row(s).transpose();
    Eigen::VectorXd expected = InverseDynamics(model, q, qd, qdd, &data);
    AddJointDynamicsTorque(model, qd, qdd, &expected);
    worst = std::max(worst, (expected - tau).cwiseAbs().maxCoeff());
  }
  worst /= out.log.tau.cwiseAbs().maxCoeff();
  std::printf("torque mismatch %.3g relative\n", worst);
  EXPECT_LT(worst, 1e-8);
  // Without feed-forward the PID lags: the loop is closed, not replayed.
  EXPECT_GT((out.log.q - out.q_ref).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(ClosedLoopTest, SaturationBoundsTheCommandedTorque) {
  const RobotModel model = MakePuma560();
  const auto reference = MakeGeneralMotion(6, 0.5);
  JointControllerOptions pid = PumaPid();
  pid.tau_max = {5.0};
  SimulationOptions options;
  options.duration = 0.5;
  const ClosedLoopLog out = SimulateClosedLoop(model, *reference, options, pid, SensorOptions{});
  EXPECT_LE(out.log.tau.cwiseAbs().maxCoeff(), 5.0);
  EXPECT_EQ(out.log.tau.cwiseAbs().maxCoeff(), 5.0);  // gravity on joint 2 needs more
}

// The controller acts on the measured q: with position noise the commanded
// torque differs from the noise-free run's, and the log's q is what it saw.
TEST(ClosedLoopTest, ControllerActsOnTheMeasuredPositions) {
  const RobotModel model = MakePuma560();
  const auto reference = MakeGeneralMotion(6, 0.2);
  SimulationOptions options;
  options.duration = 0.2;
  SensorOptions noisy;
  noisy.q_noise = 1e-4;
  const ClosedLoopLog clean = SimulateClosedLoop(model, *reference, options, PumaPid(), SensorOptions{});
  const ClosedLoopLog measured = SimulateClosedLoop(model, *reference, options, PumaPid(), noisy);
  // First sample: the same state, q off by the noise, τ off by Kp·noise + Kd·0 + Ki·T·noise.
  const Eigen::VectorXd dq = (measured.log.q.row(0) - clean.log.q.row(0)).transpose();
  EXPECT_GT(dq.cwiseAbs().maxCoeff(), 1e-6);
  const Eigen::VectorXd dtau = (measured.log.tau.row(0) - clean.log.tau.row(0)).transpose();
  EXPECT_LT((dtau + (400.0 + 50.0 * 1e-3) * dq).norm(), 1e-9 * dtau.norm() + 1e-12);
}

TEST(ClosedLoopTest, OptionsNameTheBadField) {
  JointControllerOptions pid;
  std::string why;
  EXPECT_FALSE(pid.IsValid(6, &why));
  EXPECT_EQ(why, "kp: expected one value or 6 (one per joint), got none");
  pid = PumaPid();
  pid.kd = {1.0, 2.0};
  EXPECT_FALSE(pid.IsValid(6, &why));
  EXPECT_EQ(why, "kd: expected one value or 6 (one per joint), got 2");
  pid = PumaPid();
  pid.tau_max = {0.0};
  EXPECT_FALSE(pid.IsValid(6, &why));
  EXPECT_EQ(why, "tau_max[0]: expected a finite limit > 0 N m, got 0.000000");
}

}  // namespace
}  // namespace idbench
