#include "idbench/excitation/design_regressor.h"

#include <gtest/gtest.h>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using testing::RandomVector;

JointState RandomState(int n, std::mt19937* rng) {
  JointState x(n);
  x.q = RandomVector(n, 2.5, rng);
  x.qd = RandomVector(n, 2.0, rng);
  for (int j = 0; j < n; ++j) x.qd[j] += x.qd[j] > 0 ? 0.2 : -0.2;  // away from Coulomb's step
  x.qdd = RandomVector(n, 5.0, rng);
  return x;
}

FrictionModel FvFcIa() {
  FrictionModel f;
  f.viscous = f.coulomb = f.rotor_inertia = true;
  return f;
}

class DesignRegressorTest : public ::testing::TestWithParam<int> {
 protected:
  RobotModel model_ = testing::MakeTestRobot(GetParam());
};

// Base rows times the true base parameters are the joint torques of an
// independent algorithm: the RNEA plus the joint dynamics.
TEST_P(DesignRegressorTest, JointTorqueRowsReproduceInverseDynamics) {
  const DesignRegressor r = DesignRegressor::JointTorque(model_, FvFcIa());
  DesignRegressor::Workspace ws(model_);
  RobotData data(model_);
  std::mt19937 rng(8);
  Eigen::MatrixXd rows(r.rows_per_sample(), r.n_parameters());
  for (int trial = 0; trial < 10; ++trial) {
    const JointState x = RandomState(model_.n_dof(), &rng);
    r.Rows(x, &ws, rows);
    Eigen::VectorXd tau = InverseDynamics(model_, x.q, x.qd, x.qdd, &data);
    AddJointDynamicsTorque(model_, x.qd, x.qdd, &tau);
    EXPECT_LT(testing::RelativeError(rows * r.true_parameters(), tau), 1e-11) << "trial " << trial;
  }
}

// ∂⟨G, Rows(x)⟩/∂x by dual numbers against central differences, both models.
void ExpectStateGradientMatchesFiniteDifferences(const DesignRegressor& r, unsigned seed) {
  const RobotModel& model = r.model();
  const int n = model.n_dof();
  DesignRegressor::Workspace ws(model);
  std::mt19937 rng(seed);
  const JointState x = RandomState(n, &rng);
  Eigen::MatrixXd G(r.rows_per_sample(), r.n_parameters());
  for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = RandomVector(1, 1.0, &rng)[0];
  Eigen::VectorXd g(3 * n);
  r.StateGradient(x, G, &ws, g);
  Eigen::MatrixXd rows(r.rows_per_sample(), r.n_parameters());
  auto f = [&](const JointState& y) {
    r.Rows(y, &ws, rows);
    return (G.array() * rows.array()).sum();
  };
  Eigen::VectorXd fd(3 * n);
  const double h = 1e-6;
  for (int dir = 0; dir < 3 * n; ++dir) {
    JointState xp = x, xm = x;
    Eigen::VectorXd& vp = dir < n ? xp.q : dir < 2 * n ? xp.qd : xp.qdd;
    Eigen::VectorXd& vm = dir < n ? xm.q : dir < 2 * n ? xm.qd : xm.qdd;
    vp[dir % n] += h;
    vm[dir % n] -= h;
    fd[dir] = (f(xp) - f(xm)) / (2 * h);
  }
  EXPECT_LT((g - fd).norm(), 1e-7 * fd.norm()) << "analytic " << g.transpose() << "\nfd " << fd.transpose();
}

TEST_P(DesignRegressorTest, JointTorqueStateGradientMatchesFiniteDifferences) {
  ExpectStateGradientMatchesFiniteDifferences(DesignRegressor::JointTorque(model_, FvFcIa()), 9);
}

INSTANTIATE_TEST_SUITE_P(Robots, DesignRegressorTest, ::testing::Range(0, testing::kNumTestRobots),
                         testing::TestRobotName);

// paper6r: B1 turns about its fixed hinge axis e1, so only its J11 can be identified
// (the paper's finding); every other body has all three moments.
TEST(DesignRegressorPerBodyTest, StructurallyIdentifiableMomentsOfPaper6r) {
  const RobotModel model = MakePaper6r();
  const DesignRegressor r = DesignRegressor::PerBody(model);
  EXPECT_EQ(r.rows_per_sample(), 36);
  ASSERT_EQ(r.n_parameters(), 2 + 5 * 4);
  EXPECT_EQ(r.parameter_names()[0], model.link(0).name + ".m");
  EXPECT_EQ(r.parameter_names()[1], model.link(0).name + ".J11");  // its hinge axis
  EXPECT_EQ(r.parameter_names()[2], model.link(1).name + ".m");
  EXPECT_NEAR(r.true_parameters()[1], model.link(0).inertia.I_Bcm_B(0, 0), 1e-15);
  ExpectStateGradientMatchesFiniteDifferences(r, 10);
}

TEST(DesignRegressorPerBodyTest, RefusesNonPrincipalAxes) {
  EXPECT_THROW(DesignRegressor::PerBody(testing::MakeTiltedRobot()), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
