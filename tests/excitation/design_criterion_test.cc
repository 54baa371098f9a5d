#include "idbench/excitation/design_criterion.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <random>

namespace idbench {
namespace {

Eigen::MatrixXd RandomMatrix(int rows, int cols, std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd A(rows, cols);
  for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = n(*rng);
  return A;
}

// W = U diag(σ) Vᵀ with known singular values (independent truth).
Eigen::MatrixXd MatrixWithSingularValues(int rows, const Eigen::VectorXd& sigma, std::mt19937* rng) {
  const int p = static_cast<int>(sigma.size());
  const Eigen::MatrixXd U = Eigen::HouseholderQR<Eigen::MatrixXd>(RandomMatrix(rows, p, rng)).householderQ() *
                            Eigen::MatrixXd::Identity(rows, p);
  const Eigen::MatrixXd V = Eigen::HouseholderQR<Eigen::MatrixXd>(RandomMatrix(p, p, rng)).householderQ();
  return U * sigma.asDiagonal() * V.transpose();
}

TEST(DesignCriterionTest, IdentifiabilityFromKnownSingularValues) {
  std::mt19937 rng(3);
  Eigen::VectorXd sigma(4);
  sigma << 50.0, 7.0, 2.0, 0.5;
  const Eigen::MatrixXd W = MatrixWithSingularValues(30, sigma, &rng);
  const Identifiability id = ComputeIdentifiability(W);
  EXPECT_EQ(id.rank, 4);
  EXPECT_NEAR(id.sigma_max, 50.0, 1e-12);
  EXPECT_NEAR(id.sigma_min, 0.5, 1e-13);
  EXPECT_NEAR(id.cond, 100.0, 1e-10);  // cond(W), not cond(WᵀW) = 1e4
  EXPECT_NEAR(id.log_det, 2.0 * (sigma.array() / std::sqrt(30.0)).log().sum(), 1e-12);
  EXPECT_NEAR(std::log(id.cond), EvaluateDesignCriterion(DesignCriterion::kLogCond, W), 1e-12);
  EXPECT_NEAR(-id.log_det / 4.0, EvaluateDesignCriterion(DesignCriterion::kLogDet, W), 1e-12);
  // Column scaling changes cond but not the normalised cond.
  Eigen::VectorXd scale(4);
  scale << 1e3, 1.0, 1e-2, 5.0;
  const Identifiability scaled = ComputeIdentifiability(W * scale.asDiagonal());
  EXPECT_NEAR(scaled.cond_normalised, id.cond_normalised, 1e-9 * id.cond_normalised);
  EXPECT_GT(std::abs(scaled.cond - id.cond), 1.0);
}

TEST(DesignCriterionTest, IllConditionedMatrixUsesTheSvdPath) {
  std::mt19937 rng(4);
  Eigen::VectorXd sigma(3);
  sigma << 1.0, 1e-3, 1e-8;  // cond 1e8: WᵀW would lose λ_min
  const Eigen::MatrixXd W = MatrixWithSingularValues(40, sigma, &rng);
  EXPECT_NEAR(EvaluateDesignCriterion(DesignCriterion::kLogCond, W), std::log(1e8), 1e-6);
}

TEST(DesignCriterionTest, RankDeficientIsInfiniteAndNamedSo) {
  std::mt19937 rng(5);
  Eigen::MatrixXd W = RandomMatrix(20, 3, &rng);
  W.col(2) = 2.0 * W.col(0) - W.col(1);
  EXPECT_EQ(ComputeIdentifiability(W).rank, 2);
  EXPECT_TRUE(std::isinf(ComputeIdentifiability(W).cond));
  Eigen::MatrixXd G;
  EXPECT_TRUE(std::isinf(EvaluateDesignCriterion(DesignCriterion::kLogCond, W, &G)));
  EXPECT_EQ(G.norm(), 0.0);
}

TEST(DesignCriterionTest, NamesRoundTrip) {
  for (const std::string& name : DesignCriterionNames()) {
    DesignCriterion criterion;
    ASSERT_TRUE(ParseDesignCriterion(name, &criterion)) << name;
    EXPECT_EQ(DesignCriterionName(criterion), name);
  }
  DesignCriterion criterion;
  std::string why;
  EXPECT_FALSE(ParseDesignCriterion("cond2", &criterion, &why));
  EXPECT_EQ(why, "criterion: expected cond, cond-normalised, logdet or hybrid, got 'cond2'");
}

// The analytic gradient (dσ_i = u_iᵀ dW v_i) against central differences.
class DesignCriterionGradientTest : public ::testing::TestWithParam<DesignCriterion> {};

TEST_P(DesignCriterionGradientTest, MatchesCentralDifferences) {
  std::mt19937 rng(6);
  Eigen::MatrixXd W = RandomMatrix(25, 5, &rng);
  W.col(3) *= 40.0;  // different column scales
  Eigen::MatrixXd G;
  const double c = EvaluateDesignCriterion(GetParam(), W, &G);
  ASSERT_TRUE(std::isfinite(c));
  Eigen::MatrixXd fd(W.rows(), W.cols());
  for (Eigen::Index i = 0; i < W.size(); ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(W.data()[i]));
    Eigen::MatrixXd Wp = W, Wm = W;
    Wp.data()[i] += h;
    Wm.data()[i] -= h;
    fd.data()[i] = (EvaluateDesignCriterion(GetParam(), Wp) - EvaluateDesignCriterion(GetParam(), Wm)) / (2 * h);
  }
  EXPECT_LT((G - fd).norm(), 1e-5 * fd.norm());  // the bar; WᵀW costs ~1e-12 in c
}

INSTANTIATE_TEST_SUITE_P(AllCriteria, DesignCriterionGradientTest,
                         ::testing::Values(DesignCriterion::kLogCond, DesignCriterion::kLogCondNormalised,
                                           DesignCriterion::kLogDet, DesignCriterion::kHybrid));

}  // namespace
}  // namespace idbench
