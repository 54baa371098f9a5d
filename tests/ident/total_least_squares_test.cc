// Total least squares (total_least_squares.h) against independent truth: the
// base parameters of a noise-free paper6r log; the smallest right singular
// vector of the dense column-scaled [W τ] from Eigen's JacobiSVD; and, over
// Monte Carlo draws, the spread of the estimates that σ claims.
#include "idbench/ident/total_least_squares.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <random>

#include "idbench/ident/residual_covariance.h"
#include "joint_torque_experiment.h"

namespace idbench {
namespace {

double RelativeError(const Eigen::VectorXd& beta, const Eigen::VectorXd& truth) {
  return (beta - truth).norm() / truth.norm();
}

TEST(TotalLeastSquaresTest, NoiseFreeLogRecoversTheBaseParameters) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 400);
  const LinearFit fit = SolveTls(e.W, e.tau, 6);
  EXPECT_TRUE(fit.solve.converged) << fit.solve.message;
  EXPECT_EQ(fit.solve.iterations, 1);
  EXPECT_LT(RelativeError(fit.beta, e.beta_true), 1e-9);
  // Per parameter too, against its own size or the largest's 1e-9.
  const double largest = e.beta_true.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < fit.beta.size(); ++k) {
    EXPECT_NEAR(fit.beta[k], e.beta_true[k], 1e-9 * std::max(std::abs(e.beta_true[k]), 1e-3 * largest)) << k;
  }
}

// With noise in W and τ, TLS is not least squares: it is the smallest right
// singular vector of the column-scaled [W τ], here from Eigen's JacobiSVD of
// the dense matrix (a few hundred rows), where SolveTls folds the rows first.
TEST(TotalLeastSquaresTest, EqualsTheSmallestSingularVectorOfTheDenseScaledMatrix) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 60);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd W = e.W;
  for (Eigen::Index r = 0; r < W.rows(); ++r) {
    for (Eigen::Index c = 0; c < W.cols(); ++c) W(r, c) += 0.01 * W.col(c).norm() / std::sqrt(double(W.rows())) * normal(rng);
  }
  const Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, 0.5), 3);
  const Eigen::Index p = W.cols();
  ASSERT_GT(W.rows(), 300);

  // The dense truth.
  Eigen::MatrixXd C(W.rows(), p + 1);
  C << W, tau;
  const Eigen::VectorXd scale = C.colwise().norm().transpose().cwiseInverse();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C * scale.asDiagonal(), Eigen::ComputeThinV);
  const Eigen::VectorXd v = svd.matrixV().col(p);
  const Eigen::VectorXd beta_svd = -(scale.head(p).cwiseProduct(v.head(p))) / (v[p] * scale[p]);

  const LinearFit fit = SolveTls(W, tau, 6);
  ASSERT_TRUE(fit.solve.converged) << fit.solve.message;
  ASSERT_EQ(fit.rank, p);
  EXPECT_LT(RelativeError(fit.beta, beta_svd), 1e-9) << "TLS from the folded factors against the dense SVD";
  // And it is not OLS: the regressor noise moves it.
  const LinearFit ols = SolveOls(W, tau, 6);
  EXPECT_GT(RelativeError(ols.beta, beta_svd), 1e-6);
  // The TLS normal equations (WᵀW − s² D⁻²) β = Wᵀτ, s the smallest singular value.
  const double s = svd.singularValues()[p];
  Eigen::MatrixXd H = W.transpose() * W;
  H.diagonal() -= (s * s) * scale.head(p).cwiseAbs2().cwiseInverse();
  EXPECT_LT((H * fit.beta - W.transpose() * tau).norm() / (W.transpose() * tau).norm(), 1e-8);
}

// σ of TLS (the linearised sandwich, batch means) against the spread of its
// estimates over draws of white torque noise and noise in the regressor.
TEST(TotalLeastSquaresTest, SigmaAgreesWithTheMonteCarloSpread) {
  const Experiment e = MakeExperiment(/*with_friction=*/true, 500);
  const Eigen::Index p = e.W.cols();
  constexpr int kDraws = 300;
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd betas(p, kDraws);
  Eigen::VectorXd mean_sigma = Eigen::VectorXd::Zero(p);
  const Eigen::VectorXd column_rms = e.W.colwise().norm().transpose() / std::sqrt(double(e.W.rows()));
  for (int d = 0; d < kDraws; ++d) {
    Eigen::MatrixXd W = e.W;
    for (Eigen::Index r = 0; r < W.rows(); ++r) {
      for (Eigen::Index c = 0; c < p; ++c) W(r, c) += 1e-3 * column_rms[c] * normal(rng);
    }
    Eigen::VectorXd tau = e.tau;
    for (Eigen::Index r = 0; r < tau.size(); ++r) tau[r] += 0.5 * normal(rng);
    LinearFit fit = SolveTls(W, tau, 6);
    ASSERT_TRUE(fit.solve.converged);
    ApplyStackedScoreCovariance(W, tau, 6, &fit);
    betas.col(d) = fit.beta;
    mean_sigma += fit.sigma / kDraws;
  }
  const Eigen::VectorXd mean = betas.rowwise().mean();
  const Eigen::VectorXd spread =
      ((betas.colwise() - mean).rowwise().squaredNorm() / (kDraws - 1)).cwiseSqrt();
  const Eigen::ArrayXd ratio = mean_sigma.array() / spread.array();
  std::printf("TLS sigma / spread: min %.3f, max %.3f over %d parameters\n", ratio.minCoeff(), ratio.maxCoeff(),
              static_cast<int>(p));
  for (Eigen::Index k = 0; k < p; ++k) {
    EXPECT_GT(ratio[k], 0.75) << k;
    EXPECT_LT(ratio[k], 1.25) << k;
  }
}

}  // namespace
}  // namespace idbench
