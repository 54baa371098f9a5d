#include "idbench/ident/base_parameters.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"

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

// Actuator-side terms through a gear ratio N scale their columns by N (Fc)
// and N² (Fv, Ia); the link columns do not. The base set is the same at any N
// up to the transmission's bound and beyond it (N = 1e5: 18 of 52 on the old
// code, which compared every column with the largest), and the rotor
// inertia absorbs link 1's Izz as Iam1 + Izz1/N² (by virtual work: motor 1
// and link 1 turn together, N rad to 1).
TEST(BaseParametersPuma560Test, GearRatiosDoNotChangeTheBaseSet) {
  const RobotModel puma = MakePuma560();
  auto base_through = [&](double N) {
    FrictionModel friction;
    friction.viscous = friction.coulomb = friction.rotor_inertia = true;
    friction.actuator_from_joint = Eigen::MatrixXd::Identity(6, 6) * N;
    return ComputeBaseParameters(puma, friction);
  };
  const BaseParameters direct = base_through(1.0);
  const std::vector<std::string> names = StandardParameterNames(puma, FrictionModel{.viscous = true, .coulomb = true,
                                                                                    .rotor_inertia = true});
  for (double N : {160.0, 1e4, 1e5}) {
    const BaseParameters geared = base_through(N);
    EXPECT_EQ(geared.n_base(), direct.n_base()) << "N = " << N;
    EXPECT_EQ(geared.independent, direct.independent) << "N = " << N;
    if (N > 1e4) continue;  // below 1e-9 the combination's entries are not kept
    // Iam1's base parameter (standard column 62: link 1's Fv, Fc, Ia after 60 inertial).
    const auto at = std::find(geared.independent.begin(), geared.independent.end(), 62);
    ASSERT_NE(at, geared.independent.end()) << "N = " << N;
    const Eigen::Index k = at - geared.independent.begin();
    EXPECT_NEAR(geared.combination(k, 9), 1.0 / (N * N), 1e-6 / (N * N)) << "N = " << N << ": " << names[9];
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, BaseParametersTest, ::testing::Range(0, testing::kNumTestRobots),
                         testing::TestRobotName);

}  // namespace
}  // namespace idbench
