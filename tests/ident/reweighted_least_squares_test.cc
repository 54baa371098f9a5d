// Iteratively reweighted least squares (reweighted_least_squares.h) against
// independent truth: the base parameters of a noise-free paper6r log; the
// same log with 5 % of its torques replaced by gross outliers, where OLS is
// pulled away and IRLS is not; and, over Monte Carlo draws of clean noise,
// the spread of the estimates that σ claims.
#include "idbench/ident/reweighted_least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "idbench/ident/residual_covariance.h"
#include "joint_torque_experiment.h"

namespace idbench {
namespace {

// ‖β − β_true‖ in the metric of the regressor, relative to ‖W β_true‖: how
// far the prediction moves, whatever the parameters' units.
double PredictionError(const Eigen::MatrixXd& W, const Eigen::VectorXd& beta, const Eigen::VectorXd& truth) {
  return (W * (beta - truth)).norm() / (W * truth).norm();
}

TEST(ReweightedLeastSquaresTest, NoiseFreeLogRecoversTheBaseParameters) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 400);
  for (RobustLoss loss : {RobustLoss::kHuber, RobustLoss::kTukey}) {
    IrlsOptions options;
    options.loss = loss;
    const LinearFit fit = SolveIrls(e.W, e.tau, 6, options);
    EXPECT_TRUE(fit.solve.converged) << fit.solve.message;
    EXPECT_LE(fit.solve.iterations, 5);
    EXPECT_LT((fit.beta - e.beta_true).norm() / e.beta_true.norm(), 1e-9) << fit.solve.message;
  }
}

// 5 % of the torques (every joint's) replaced by gross errors of ±(20 … 60) ×
// the noise; the truth is the noise-free β.
TEST(ReweightedLeastSquaresTest, GrossOutliersMoveOlsAndNotIrls) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 1000);
  const double noise = 0.5;  // [N m]
  Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, noise), 5);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int n_outliers = 0;
  for (Eigen::Index r = 0; r < tau.size(); ++r) {
    if (u(rng) < 0.05) {
      tau[r] += (u(rng) < 0.5 ? -1.0 : 1.0) * noise * (20.0 + 40.0 * u(rng));
      ++n_outliers;
    }
  }
  const LinearFit ols = SolveOls(e.W, tau, 6);
  const Eigen::VectorXd clean = AddNoise(e.tau, Eigen::VectorXd::Constant(6, noise), 5);
  const LinearFit ols_clean = SolveOls(e.W, clean, 6);
  for (RobustLoss loss : {RobustLoss::kHuber, RobustLoss::kTukey}) {
    IrlsOptions options;
    options.loss = loss;
    const LinearFit irls = SolveIrls(e.W, tau, 6, options);
    ASSERT_TRUE(irls.solve.converged) << irls.solve.message;
    const double error_ols = PredictionError(e.W, ols.beta, e.beta_true);
    const double error_irls = PredictionError(e.W, irls.beta, e.beta_true);
    const double error_clean = PredictionError(e.W, ols_clean.beta, e.beta_true);
    std::printf("%d outliers of %d rows, %s: prediction error OLS %.3g, IRLS %.3g (%d passes), OLS without the "
                "outliers %.3g; parameter error OLS %.3g, IRLS %.3g\n",
                n_outliers, static_cast<int>(tau.size()), std::string(kRobustLossNames.Name(loss)).c_str(),
                error_ols, error_irls, irls.solve.iterations, error_clean,
                (ols.beta - e.beta_true).norm() / e.beta_true.norm(),
                (irls.beta - e.beta_true).norm() / e.beta_true.norm());
    EXPECT_LT(error_irls, 0.2 * error_ols);
    EXPECT_LT(error_irls, 2.0 * error_clean);
    // The robust scale is the noise's, not the outliers'.
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(irls.joint_sigma[j], noise, 0.15 * noise) << j;
  }
}

// σ of IRLS (the weighted fit's batch-means sandwich) against the spread of
// its estimates over draws of clean Gaussian noise.
TEST(ReweightedLeastSquaresTest, SigmaAgreesWithTheMonteCarloSpread) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 500);
  const Eigen::Index p = e.W.cols();
  constexpr int kDraws = 300;
  Eigen::MatrixXd betas(p, kDraws);
  Eigen::VectorXd mean_sigma = Eigen::VectorXd::Zero(p);
  const Eigen::VectorXd joint_noise = (Eigen::VectorXd(6) << 0.5, 1.0, 0.4, 0.2, 0.1, 0.1).finished();
  int max_passes = 0;
  for (int d = 0; d < kDraws; ++d) {
    const Eigen::VectorXd tau = AddNoise(e.tau, joint_noise, 100 + d);
    LinearFit fit = SolveIrls(e.W, tau, 6);
    ASSERT_TRUE(fit.solve.converged) << fit.solve.message;
    max_passes = std::max(max_passes, fit.solve.iterations);
    ApplyStackedScoreCovariance(e.W, tau, 6, &fit);
    betas.col(d) = fit.beta;
    mean_sigma += fit.sigma / kDraws;
  }
  const Eigen::VectorXd mean = betas.rowwise().mean();
  const Eigen::VectorXd spread = ((betas.colwise() - mean).rowwise().squaredNorm() / (kDraws - 1)).cwiseSqrt();
  const Eigen::ArrayXd ratio = mean_sigma.array() / spread.array();
  std::printf("IRLS sigma / spread: min %.3f, max %.3f over %d parameters; at most %d passes\n", ratio.minCoeff(),
              ratio.maxCoeff(), static_cast<int>(p), max_passes);
  for (Eigen::Index k = 0; k < p; ++k) {
    EXPECT_GT(ratio[k], 0.75) << k;
    EXPECT_LT(ratio[k], 1.25) << k;
  }
}

TEST(ReweightedLeastSquaresTest, ReachesItsIterationLimitWithAVerdict) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 300);
  Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, 0.5), 9);
  for (Eigen::Index r = 0; r < tau.size(); r += 17) tau[r] += 30.0;
  IrlsOptions options;
  options.max_iterations = 1;
  const LinearFit fit = SolveIrls(e.W, tau, 6, options);
  EXPECT_FALSE(fit.solve.converged);
  EXPECT_EQ(fit.solve.iterations, 1);
  EXPECT_NE(fit.solve.message.find("not converged"), std::string::npos) << fit.solve.message;
  options.max_iterations = 0;
  EXPECT_THROW(SolveIrls(e.W, tau, 6, options), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
