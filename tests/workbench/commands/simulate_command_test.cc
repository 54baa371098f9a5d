// SimulateJointLog as a library call with typed options: the log is sampled
// at the sensor rate, and with noise-free sensors each sample's torques are
// the inverse dynamics of its own q, qd, qdd plus the robot's joint friction
// and rotor inertia (inverse_dynamics.h), independently of how Bullet got there.
#include "idbench/workbench/commands/simulate_command.h"

#include <gtest/gtest.h>


#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

TEST(SimulateCommandTest, TorquesAreTheInverseDynamicsOfEachSample) {
  const RobotModel model = MakePuma560();
  SimulateOptions options;
  options.trajectory = "general";
  options.duration = 2.0;
  options.sensors.rate_hz = 100.0;
  std::string why;
  ASSERT_TRUE(options.IsValid(&why)) << why;
  const JointLog log = SimulateJointLog(model, options);
  ASSERT_EQ(log.n_dof(), 6);
  ASSERT_TRUE(log.has_derivatives());
  ASSERT_GE(log.n_samples(), 200);
  RobotData data(model);
  for (int s = 0; s < log.n_samples(); ++s) {
    if (s > 0) EXPECT_NEAR(log.t[s] - log.t[s - 1], 0.01, 1e-12) << s;
    const Eigen::VectorXd q = log.q.row(s).transpose(), qd = log.qd.row(s).transpose(),
                          qdd = log.qdd.row(s).transpose();
    Eigen::VectorXd tau = InverseDynamics(model, q, qd, qdd, &data);
    AddJointDynamicsTorque(model, qd, qdd, &tau);
    const Eigen::VectorXd measured = log.tau.row(s).transpose();
    EXPECT_LT((tau - measured).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + tau.cwiseAbs().maxCoeff())) << "sample " << s;
  }
}

// A log as a robot writes it (t, q, τ; or t, q, qd, τ) identifies through the
// filter path to the filter's own floor: the simulated q, qd and τ are one
// motion. The floor is the same identification of the reference motion itself,
// sampled exactly (no simulation): 1.8e-5 and 1.7e-5 at 500 Hz. Bullet's
// semi-implicit Euler steps, logged as they were, put q half a step ahead of τ
// (0.23 and 3.8e-3).
class SimulatedRobotLogTest : public ::testing::Test {
 protected:
  // max |β − β_model| / max |β_model| of identify's OLS on `log`, read as
  // recorded (filtered where qd, qdd are missing).
  double RelativeError(JointLog log) const {
    RecordedJointLog recorded;
    recorded.lines.resize(static_cast<size_t>(log.n_samples()));
    for (size_t s = 0; s < recorded.lines.size(); ++s) recorded.lines[s] = static_cast<int>(s) + 2;
    recorded.log = std::move(log);
    IdentifyOptions identify;
    identify.data = "log.csv";
    const IdentifyReport report = IdentifyPreparedLogs(
        model_, identify, PrepareRecordedJointLog(std::move(recorded), "log.csv", identify.preparation(true)),
        std::nullopt);
    const JointTorqueIdentification& id = report.identification;
    EXPECT_TRUE(report.parallel_filter.has_value());
    return (id.beta - id.beta_model).cwiseAbs().maxCoeff() / id.beta_model.cwiseAbs().maxCoeff();
  }
  // The log without its qd (keep_qd false) and qdd columns.
  static JointLog WithoutDerivatives(JointLog log, bool keep_qd) {
    if (!keep_qd) log.qd.resize(0, 0);
    log.qdd.resize(0, 0);
    return log;
  }

  RobotModel model_ = MakePuma560();
  SimulateOptions options_ = [] {
    SimulateOptions options;  // the defaults: general motion, 10 s, dt 1 ms
    options.sensors.rate_hz = 500.0;
    return options;
  }();
  JointLog simulated_ = SimulateJointLog(model_, options_);
  JointLog exact_ = testing::SyntheticJointLog(
      model_, *LoadTrajectoryArg(options_.trajectory, model_, {.duration = options_.duration}), simulated_.t);
};

TEST_F(SimulatedRobotLogTest, PositionsAndTorquesIdentifyToTheFilterFloor) {
  const double floor = RelativeError(WithoutDerivatives(exact_, false));
  const double error = RelativeError(WithoutDerivatives(simulated_, false));
  EXPECT_LT(floor, 3e-5);
  EXPECT_LT(error, 1e-4);
  EXPECT_LT(error, 1.5 * floor);
}

TEST_F(SimulatedRobotLogTest, PositionsVelocitiesAndTorquesIdentifyToTheFilterFloor) {
  const double floor = RelativeError(WithoutDerivatives(exact_, true));
  const double error = RelativeError(WithoutDerivatives(simulated_, true));
  EXPECT_LT(floor, 3e-5);
  EXPECT_LT(error, 1e-4);
  EXPECT_LT(error, 1.5 * floor);
}

}  // namespace
}  // namespace idbench
