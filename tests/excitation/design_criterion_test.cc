#include "idbench/excitation/design_criterion.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <random>

#include "idbench/ident/linear_estimator.h"

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

// Sequential design: the criterion with given information (a p × p factor of
// the given rows) equals the criterion of the given rows concatenated with
// W, value and gradient (W's rows of the concatenation's gradient); a row
// weight of 2 equals the given rows stacked twice.
class UnionCriterionTest : public ::testing::TestWithParam<DesignCriterion> {};

TEST_P(UnionCriterionTest, EqualsTheCriterionOfTheConcatenatedRows) {
  std::mt19937 rng(11);
  const Eigen::MatrixXd Wg = RandomMatrix(40, 5, &rng);
  Eigen::MatrixXd W = RandomMatrix(12, 5, &rng);  // alone: 12 rows, still full rank
  W.col(2) *= 30.0;
  const Eigen::VectorXd tau_g = RandomMatrix(40, 1, &rng);
  for (const double weight : {1.0, 2.0}) {
    const GivenInformation given =
        GivenInformationFromFactors({CombinedFactor(Wg, tau_g)}, {weight}, {40.0}, {true});
    Eigen::MatrixXd concatenated(weight == 1.0 ? 52 : 92, 5);
    if (weight == 1.0) concatenated << Wg, W;
    else concatenated << Wg, Wg, W;  // weight 2: every given row twice
    Eigen::MatrixXd G_union, G_concatenated;
    const double c_union = EvaluateDesignCriterion(GetParam(), W, &G_union, given);
    const double c_concatenated = EvaluateDesignCriterion(GetParam(), concatenated, &G_concatenated);
    ASSERT_TRUE(std::isfinite(c_concatenated));
    EXPECT_NEAR(c_union, c_concatenated, 1e-10 * std::max(1.0, std::abs(c_concatenated))) << weight;
    ASSERT_EQ(G_union.rows(), W.rows());
    EXPECT_LT((G_union - G_concatenated.bottomRows(W.rows())).norm(), 1e-9 * G_concatenated.norm()) << weight;
    const Identifiability u = ComputeIdentifiability(W, given), c = ComputeIdentifiability(concatenated);
    EXPECT_NEAR(u.cond, c.cond, 1e-10 * c.cond);
    EXPECT_NEAR(u.cond_normalised, c.cond_normalised, 1e-10 * c.cond_normalised);
    EXPECT_NEAR(u.log_det, c.log_det, 1e-10 * std::abs(c.log_det));
    EXPECT_EQ(u.rows, c.rows);
  }
}

INSTANTIATE_TEST_SUITE_P(AllCriteria, UnionCriterionTest,
                         ::testing::Values(DesignCriterion::kLogCond, DesignCriterion::kLogCondNormalised,
                                           DesignCriterion::kLogDet, DesignCriterion::kHybrid));

// Predicted σ against the textbook formula on the concatenated rows:
// s² = ‖τ − Wg β̂‖²/(m − p) from the given rows' least-squares fit, σ_k =
// s √((AᵀA)⁻¹)_kk with A the given rows alone, then with W's rows added.
TEST(PredictedSigmaTest, IsTheWhiteNoiseSigmaOfTheGivenRowsAloneAndWithTheNewOnes) {
  std::mt19937 rng(12);
  const Eigen::MatrixXd Wg = RandomMatrix(60, 4, &rng), W = RandomMatrix(20, 4, &rng);
  const Eigen::VectorXd tau_g = Wg * Eigen::Vector4d(1.0, -2.0, 0.5, 3.0) + 0.1 * RandomMatrix(60, 1, &rng);
  const GivenInformation given = GivenInformationFromFactors({CombinedFactor(Wg, tau_g)}, {1.0}, {60.0}, {true});
  const Eigen::VectorXd beta = (Wg.transpose() * Wg).ldlt().solve(Wg.transpose() * tau_g);
  const double s2 = (tau_g - Wg * beta).squaredNorm() / (60 - 4);
  EXPECT_NEAR(given.noise_variance, s2, 1e-12 * s2);
  Eigen::MatrixXd A(80, 4);
  A << Wg, W;
  const Eigen::VectorXd alone = (s2 * (Wg.transpose() * Wg).inverse().diagonal()).cwiseSqrt();
  const Eigen::VectorXd with_new = (s2 * (A.transpose() * A).inverse().diagonal()).cwiseSqrt();
  EXPECT_LT((PredictedSigma(given) - alone).norm(), 1e-10 * alone.norm());
  EXPECT_LT((PredictedSigma(given, W) - with_new).norm(), 1e-10 * with_new.norm());
  // A given direction the rows leave undetermined: σ = ∞ there alone, finite with W.
  Eigen::MatrixXd Wd = Wg;
  Wd.col(3).setZero();
  const GivenInformation deficient = GivenInformationFromFactors({CombinedFactor(Wd, tau_g)}, {1.0}, {60.0}, {true});
  EXPECT_TRUE(std::isinf(PredictedSigma(deficient)[3]));
  EXPECT_TRUE(std::isfinite(PredictedSigma(deficient, W)[3]));
}

}  // namespace
}  // namespace idbench
