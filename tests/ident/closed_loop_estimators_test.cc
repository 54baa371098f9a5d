#include "idbench/ident/closed_loop_estimators.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "idbench/engine/closed_loop.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/base_parameter_dynamics.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"

namespace idbench {
namespace {

// puma560 (rotor inertia, viscous and Coulomb friction on every joint) under
// a PID at 500 Hz (one simulation step per sample, as the estimators
// re-simulate), tracking the general motion.
struct ClosedLoopExperiment {
  RobotModel model = MakePuma560();
  FrictionModel friction{.viscous = true, .coulomb = true, .rotor_inertia = true};
  BaseParameters base = ComputeBaseParameters(model, friction);
  Eigen::VectorXd beta_true = base.combination * StandardParameters(model, friction);
  std::unique_ptr<Trajectory> reference = MakeGeneralMotion(6, 4.0);
  ClosedLoopEstimatorOptions options;
  SimulationOptions simulation;

  ClosedLoopExperiment() {
    options.controller.kp = {400.0};
    options.controller.kd = {20.0};
    options.controller.ki = {50.0};

    simulation.dt = 2e-3;
    simulation.duration = reference->duration();
  }
  JointLog Run(const SensorOptions& sensors) const {
    SensorOptions at_rate = sensors;
    at_rate.rate_hz = 1.0 / simulation.dt;
    return SimulateClosedLoop(model, *reference, simulation, options.controller, at_rate).log;
  }
  double Error(const Eigen::VectorXd& beta) const { return (beta - beta_true).norm() / beta_true.norm(); }
};

// The estimate's forward dynamics are the robot's: M q̈ + h = τ for the
// true β, against the Newton–Euler inverse dynamics with the drive terms.
TEST(BaseParameterDynamicsTest, TrueParametersGiveTheRobotsAccelerations) {
  const ClosedLoopExperiment e;
  BaseParameterDynamics dynamics(e.model, e.friction, e.base, e.beta_true);
  const JointState x = e.reference->At(1.3);
  RobotData data(e.model);
  Eigen::VectorXd tau = InverseDynamics(e.model, x.q, x.qd, x.qdd, &data);
  AddJointDynamicsTorque(e.model, x.qd, x.qdd, &tau);
  Eigen::VectorXd qdd;
  dynamics.Accelerations(x.q, x.qd, tau, &qdd);
  EXPECT_LT((qdd - x.qdd).norm(), 1e-10 * x.qdd.norm());
}

// Noise-free closed loop, q, qd, qdd read: OLS, IV and DIDIM recover the base
// parameters (measured: OLS 9.6e-15, IV 4.6e-12 in 3 iterations, DIDIM
// 5.4e-15 in 1). IV starts 5 % off and iterates back; DIDIM starts at OLS, as
// Gautier et al. do: from 5 % off its fixed-point map, which goes through
// (W_sᵀW_s)⁻¹, amplifies the weakly excited directions of this 4 s motion
// and the estimate's mass matrix stops being positive definite (iteration 21).
TEST(ClosedLoopEstimatorsTest, NoiseFreeLogGivesTheTrueBaseParameters) {
  ClosedLoopExperiment e;
  const JointLog log = e.Run(SensorOptions{});
  const LinearFit ols = SolveOls(StackBaseRegressor(e.model, e.friction, e.base, log), StackTorques(log), 6);
  std::printf("OLS relative error %.3g\n", e.Error(ols.beta));
  EXPECT_LT(e.Error(ols.beta), 1e-9);
  for (ClosedLoopMethod method : {ClosedLoopMethod::kInstrumentalVariables, ClosedLoopMethod::kDidim}) {
    const bool iv = method == ClosedLoopMethod::kInstrumentalVariables;
    e.options.method = method;
    e.options.tolerance = 1e-11;
    const Eigen::VectorXd start = iv ? Eigen::VectorXd(1.05 * e.beta_true) : ols.beta;
    const ClosedLoopEstimate estimate =
        EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, start, e.options);
    std::printf("%s: %s, relative error %.3g\n", iv ? "IV" : "DIDIM", estimate.message.c_str(),
                e.Error(estimate.beta));
    EXPECT_TRUE(estimate.converged) << estimate.message;
    EXPECT_LT(e.Error(estimate.beta), 1e-9);
    EXPECT_TRUE(estimate.sigma.allFinite());
  }
}

// A start whose mass matrix is not positive definite (OLS on a poorly
// excited log can give one) ends the iteration with a verdict, not a throw.
TEST(ClosedLoopEstimatorsTest, AnEstimateThatIsNoMechanismIsReportedAsDiverged) {
  ClosedLoopExperiment e;
  e.simulation.duration = 0.2;
  const JointLog log = e.Run(SensorOptions{});
  const ClosedLoopEstimate estimate =
      EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, -e.beta_true, e.options);
  EXPECT_FALSE(estimate.converged);
  EXPECT_EQ(estimate.iterations, 0);
  EXPECT_EQ(estimate.message, "diverged at iteration 1: re-simulating the estimate failed (the estimate's mass "
                              "matrix is not positive definite)");
}

TEST(ClosedLoopEstimatorsTest, RefusesWhatDoesNotFit) {
  ClosedLoopExperiment e;
  e.simulation.duration = 0.2;
  SensorOptions no_derivatives;
  no_derivatives.record_derivatives = false;
  const JointLog log = e.Run(no_derivatives);
  e.options.method = ClosedLoopMethod::kInstrumentalVariables;
  try {
    EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, e.beta_true, e.options);
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "closed-loop estimator: instrumental variables need the log's qd and qdd");
  }
  e.options.max_iterations = 0;
  EXPECT_THROW(EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, e.beta_true, e.options),
               std::invalid_argument);
}

// The position error of an estimate against a second algorithm: the robot
// with every mass, inertia and drive term 10 % heavier simulated by Bullet in
// the same closed loop gives Q'; re-simulating the lighter robot's log with
// the heavier robot's β (the regressor's forward dynamics) must give
// ‖Q − Q'‖_F / ‖Q‖_F. The true β gives the log back (round-off).
TEST(ClosedLoopEstimatorsTest, PositionErrorIsTheHeavierRobotsBulletTrajectory) {
  ClosedLoopExperiment e;
  e.simulation.duration = 2.0;
  const JointLog log = e.Run(SensorOptions{});
  std::vector<Link> links = e.model.links();
  for (Link& link : links) {
    link.inertia.mass *= 1.1;
    link.inertia.I_Bcm_B *= 1.1;
    link.dynamics.viscous *= 1.1;
    link.dynamics.coulomb *= 1.1;
    link.dynamics.rotor_inertia *= 1.1;
  }
  const RobotModel heavier("heavier", links, e.model.gravity_W());
  SensorOptions at_rate;
  at_rate.rate_hz = 1.0 / e.simulation.dt;
  const JointLog heavier_log =
      SimulateClosedLoop(heavier, *e.reference, e.simulation, e.options.controller, at_rate).log;
  const Eigen::VectorXd beta_heavier = e.base.combination * StandardParameters(heavier, e.friction);
  EXPECT_LT((beta_heavier - 1.1 * e.beta_true).norm(), 1e-12 * beta_heavier.norm());
  const double expected = (heavier_log.q - log.q).norm() / log.q.norm();
  const double error =
      ClosedLoopPositionError(e.model, e.friction, e.base, log, *e.reference, beta_heavier, e.options.controller);
  const double at_truth =
      ClosedLoopPositionError(e.model, e.friction, e.base, log, *e.reference, e.beta_true, e.options.controller);
  std::printf("position error: heavier %.6g (Bullet %.6g), true %.3g\n", error, expected, at_truth);
  EXPECT_GT(expected, 1e-5);
  EXPECT_NEAR(error, expected, 1e-6 * expected);
  EXPECT_LT(at_truth, 1e-9);
  EXPECT_THROW(ClosedLoopPositionError(e.model, e.friction, e.base, log, *e.reference, -e.beta_true,
                                       e.options.controller),
               std::runtime_error);
}

// A log whose torques are read as held (each sample's the mean of the hold
// ending there and the one starting there, as logs/ reads them): the true β
// is DIDIM's fixed point when it reads its re-simulation's q̈ the same way;
// pairing that τ with the one-sided q̈ of the command just given, DIDIM
// leaves the truth. (From a start 2 % off, this 2 s motion excites too
// little for DIDIM's map to contract: NoiseFreeLogGivesTheTrueBaseParameters.)
TEST(ClosedLoopEstimatorsTest, DidimReadsHeldTorquesAcrossTheTwoHolds) {
  ClosedLoopExperiment e;
  e.simulation.duration = 2.0;
  JointLog log = e.Run(SensorOptions{});
  for (Eigen::Index k = log.tau.rows() - 1; k > 0; --k) log.tau.row(k) = 0.5 * (log.tau.row(k - 1) + log.tau.row(k));
  e.options.method = ClosedLoopMethod::kDidim;
  e.options.tolerance = 1e-11;
  const Eigen::VectorXd start = e.beta_true;
  e.options.torque_held = true;
  const ClosedLoopEstimate held = EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, start, e.options);
  e.options.torque_held = false;
  const ClosedLoopEstimate one_sided =
      EstimateClosedLoop(e.model, e.friction, e.base, log, *e.reference, start, e.options);
  std::printf("DIDIM on held torques: across the holds %.3g (%s), one-sided %.3g\n", e.Error(held.beta),
              held.message.c_str(), e.Error(one_sided.beta));
  EXPECT_TRUE(held.converged) << held.message;
  EXPECT_LT(e.Error(held.beta), 1e-9);
  EXPECT_GT(e.Error(one_sided.beta), 1e-4);
}

}  // namespace
}  // namespace idbench
