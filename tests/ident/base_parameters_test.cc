#include "idbench/ident/base_parameters.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using testing::RandomVector;

class BaseParametersTest : public ::testing::TestWithParam<int> {
 protected:
  RobotModel model_ = testing::MakeTestRobot(GetParam());
};

TEST_P(BaseParametersTest, BaseRegressorReproducesEveryTorqueOnFreshStates) {
  FrictionModel friction;
  friction.viscous = friction.coulomb = true;
  const BaseParameters base = ComputeBaseParameters(model_, friction);
  Eigen::VectorXd pi = StandardParameters(model_, friction);
  const int n = model_.n_dof();
  pi.tail(2 * n).setLinSpaced(0.5, 3.0);
  const Eigen::VectorXd beta = base.combination * pi;
  // Independent check of the count: the numerical rank by SVD on other states.
  std::mt19937 rng(99);
  RobotData d(model_);
  Eigen::MatrixXd Y, W(60 * n, pi.size());
  for (int s = 0; s < 60; ++s) {
    ComputeJointTorqueRegressor(model_, friction, RandomVector(n, 3.0, &rng), RandomVector(n, 3.0, &rng),
                                RandomVector(n, 10.0, &rng), &d, &Y);
    W.middleRows(s * n, n) = Y;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  int rank = 0;
  while (rank < svd.singularValues().size() && svd.singularValues()[rank] > 1e-9 * svd.singularValues()[0]) ++rank;
  EXPECT_EQ(base.n_base(), rank);
  EXPECT_LT(testing::RelativeError(base.Reduce(W) * beta, W * pi), 1e-10);
}

TEST(BaseParametersPaper6rTest, FirstBodyKeepsOnlyItsAxialInertia) {
  // B1 turns about its own x axis, fixed: of its 10 parameters only Ixx
  // (about the hinge point) affects any torque.
  const BaseParameters base = ComputeBaseParameters(MakePaper6r(), FrictionModel{});
  int b1_unexcited = 0;
  for (int c : base.unexcited) b1_unexcited += c < 10;
  EXPECT_EQ(b1_unexcited, 9);
  EXPECT_GT(base.combination.col(4).cwiseAbs().maxCoeff(), 0.0);  // B1.Ixx lives in a base parameter
}

// The literature's count (Gautier & Khalil; Armstrong's PUMA): 36 inertial
// base parameters for a PUMA-type 6R arm, plus Fv and Fc of every joint.
TEST(BaseParametersPuma560Test, FortyEightBaseParametersWithViscousAndCoulombFriction) {
  FrictionModel friction;
  friction.viscous = friction.coulomb = true;
  const BaseParameters base = ComputeBaseParameters(MakePuma560(), friction);
  EXPECT_EQ(base.n_base(), 48);
  int friction_terms = 0;
  for (int c : base.independent) friction_terms += c >= 60;
  EXPECT_EQ(friction_terms, 12);
}

INSTANTIATE_TEST_SUITE_P(Robots, BaseParametersTest, ::testing::Range(0, testing::kNumTestRobots),
                         testing::TestRobotName);

}  // namespace
}  // namespace idbench
