#include "idbench/ident/linear_estimator.h"

#include <gtest/gtest.h>

#include <random>

#include "idbench/engine/paper6r.h"
#include "idbench/engine/simulation.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/base_parameters.h"

namespace idbench {
namespace {

// Base regressor and torques from a Bullet simulation of paper6r, general motion.
struct Experiment {
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  Eigen::VectorXd beta_true;
};

Experiment MakeExperiment(int stride) {
  const RobotModel model = MakePaper6r();
  const FrictionModel friction;
  const BaseParameters base = ComputeBaseParameters(model, friction);
  const auto motion = MakeGeneralMotion(6, 4.0);
  SimulationOptions options;
  options.duration = 4.0;
  const SimulationLog log = Simulate(model, *motion, options);
  const int n_samples = static_cast<int>(log.steps.size()) / stride;
  Experiment e{Eigen::MatrixXd(6 * n_samples, base.n_base()), Eigen::VectorXd(6 * n_samples),
               base.combination * StandardParameters(model, friction)};
  RobotData d(model);
  Eigen::MatrixXd Y;
  for (int s = 0; s < n_samples; ++s) {
    const LogStep& step = log.steps[static_cast<size_t>(s * stride)];
    ComputeJointTorqueRegressor(model, friction, step.q, step.qd, step.qdd, &d, &Y);
    e.W.middleRows(6 * s, 6) = base.Reduce(Y);
    e.tau.segment(6 * s, 6) = step.tau;
  }
  return e;
}

TEST(LinearEstimatorTest, NoiseFreeBulletDataRecoversTheBaseParameters) {
  const Experiment e = MakeExperiment(4);
  for (const LinearFit& fit : {SolveOls(e.W, e.tau, 6), SolveWls(e.W, e.tau, 6)}) {
    EXPECT_LT((fit.beta - e.beta_true).norm() / e.beta_true.norm(), 1e-8);
    // Per parameter, relative to its size (floored for parameters that are
    // zero in paper6r, e.g. the lateral first moments of the cylinders).
    const Eigen::VectorXd scale = e.beta_true.cwiseAbs().cwiseMax(1e-3 * e.beta_true.cwiseAbs().maxCoeff());
    EXPECT_LT((fit.beta - e.beta_true).cwiseAbs().cwiseQuotient(scale).maxCoeff(), 1e-8);
  }
}

// The predicted covariance describes the empirical spread of estimates over
// seeded noise draws (σ 0.5 N m on joints 1–3, 0.05 N m on 4–6).
TEST(LinearEstimatorTest, PredictedSigmaMatchesMonteCarloSpread) {
  const Experiment e = MakeExperiment(8);
  const Eigen::VectorXd noise_sigma = (Eigen::VectorXd(6) << 0.5, 0.5, 0.5, 0.05, 0.05, 0.05).finished();
  std::mt19937 rng(2024);
  std::normal_distribution<double> normal;
  const int trials = 100;
  Eigen::MatrixXd estimates(e.W.cols(), trials);
  Eigen::VectorXd predicted = Eigen::VectorXd::Zero(e.W.cols());
  for (int t = 0; t < trials; ++t) {
    Eigen::VectorXd tau = e.tau;
    for (Eigen::Index r = 0; r < tau.size(); ++r) tau[r] += noise_sigma[r % 6] * normal(rng);
    const LinearFit fit = SolveWls(e.W, tau, 6);
    estimates.col(t) = fit.beta;
    predicted += fit.sigma / trials;
  }
  const Eigen::VectorXd mean = estimates.rowwise().mean();
  const Eigen::VectorXd spread =
      ((estimates.colwise() - mean).rowwise().squaredNorm() / (trials - 1)).cwiseSqrt();
  for (Eigen::Index k = 0; k < spread.size(); ++k) {
    EXPECT_NEAR(spread[k] / predicted[k], 1.0, 0.2) << "base parameter " << k;
  }
}

TEST(LinearEstimatorTest, RejectsTooFewEquations) {
  EXPECT_THROW(SolveOls(Eigen::MatrixXd::Zero(6, 10), Eigen::VectorXd::Zero(6), 6), std::invalid_argument);
  EXPECT_THROW(SolveOls(Eigen::MatrixXd::Zero(12, 2), Eigen::VectorXd::Zero(11), 6), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
