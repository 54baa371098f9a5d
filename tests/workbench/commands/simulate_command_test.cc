// SimulateJointLog as a library call with typed options: the log is sampled
// at the sensor rate, and with noise-free sensors each sample's torques are
// the inverse dynamics of its own q, qd, qdd plus the robot's joint friction
// and rotor inertia (inverse_dynamics.h), independently of how Bullet got there.
#include "idbench/workbench/commands/simulate_command.h"

#include <gtest/gtest.h>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"

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

}  // namespace
}  // namespace idbench
