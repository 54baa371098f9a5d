// σ from the residual as it is (residual_covariance.h) against independent
// truth: a linear model with two joints, slowly varying regressors and AR(1)
// noise of known ρ, fitted over ≥ 200 Monte Carlo draws, whose spread of β̂ is
// the true covariance. For regressors that vary slowly against the noise's
// correlation time, that spread is the white formula's σ times
// √((1 + ρ)/(1 − ρ)) (the long-run variance of AR(1) over its variance).
#include "idbench/ident/residual_covariance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "idbench/ident/linear_estimator.h"

namespace idbench {
namespace {

constexpr int kDof = 2;
constexpr int kParameters = 4;

// W (n·2 × 4), rows interleaved by joint: joint 1 [1, sin ωt, 0, ½ cos ω₂t],
// joint 2 [0, cos ωt, 1, sin ω₂t]; periods of 2000 and 3100 samples, far
// longer than the noise's correlation.
Eigen::MatrixXd SlowRegressor(Eigen::Index n) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(kDof * n, kParameters);
  for (Eigen::Index s = 0; s < n; ++s) {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(s) / 2000.0;
    const double b = 2.0 * std::numbers::pi * static_cast<double>(s) / 3100.0;
    W.row(kDof * s) << 1.0, std::sin(a), 0.0, 0.5 * std::cos(b);
    W.row(kDof * s + 1) << 0.0, std::cos(a), 1.0, std::sin(b);
  }
  return W;
}

struct MonteCarlo {
  Eigen::VectorXd spread;      // standard deviation of β̂ over the draws (the truth)
  Eigen::VectorXd mean_sigma;  // mean over the draws of the batch-means σ
  Eigen::VectorXd mean_white;  // … of the white-residual σ
  double mean_n_effective = 0.0;
  Eigen::Index min_block = 0, max_block = 0;  // the block lengths used, over the draws
};

std::string RatioText(const Eigen::ArrayXd& x) {
  std::string out;
  for (Eigen::Index k = 0; k < x.size(); ++k) out += (k ? " " : "") + std::to_string(x[k]).substr(0, 5);
  return out;
}

// OLS (or WLS) on draws τ = W β + e, e per joint AR(1) of coefficient ρ with
// stationary standard deviations 1 and sd2 (≠ 1: heteroskedastic),
// independent between joints.
// block_samples: as ApplyStackedScoreCovariance's (0: chosen from the scores).
MonteCarlo RunMonteCarlo(double rho, bool wls, double sd2, int n_draws = 400, Eigen::Index n = 10000,
                         Eigen::Index block_samples = 0) {
  const Eigen::MatrixXd W = SlowRegressor(n);
  const Eigen::Vector4d beta_true(2.0, -1.0, 0.5, 3.0);
  const Eigen::VectorXd tau0 = W * beta_true;
  const double joint_sd[kDof] = {1.0, sd2};
  std::mt19937_64 rng(1234);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd betas(kParameters, n_draws);
  MonteCarlo mc;
  mc.mean_sigma = mc.mean_white = Eigen::VectorXd::Zero(kParameters);
  Eigen::VectorXd tau(kDof * n);
  for (int d = 0; d < n_draws; ++d) {
    for (int j = 0; j < kDof; ++j) {
      // Stationary start, innovations scaled to the joint's variance.
      double e = joint_sd[j] * normal(rng);
      const double innovation = joint_sd[j] * std::sqrt(1.0 - rho * rho);
      for (Eigen::Index s = 0; s < n; ++s) {
        if (s > 0) e = rho * e + innovation * normal(rng);
        tau[kDof * s + j] = tau0[kDof * s + j] + e;
      }
    }
    LinearFit fit = wls ? SolveWls(W, tau, kDof) : SolveOls(W, tau, kDof);
    ApplyStackedScoreCovariance(W, tau, kDof, &fit, block_samples);
    EXPECT_EQ(fit.covariance_method.method, CovarianceMethod::kBatchMeans);
    const Eigen::Index block = fit.covariance_method.block_samples;
    EXPECT_EQ(fit.covariance_method.n_blocks, (n + block - 1) / block);
    mc.min_block = d == 0 ? block : std::min(mc.min_block, block);
    mc.max_block = std::max(mc.max_block, block);
    betas.col(d) = fit.beta;
    mc.mean_sigma += fit.sigma / static_cast<double>(n_draws);
    mc.mean_white += fit.sigma_white / static_cast<double>(n_draws);
    mc.mean_n_effective += fit.covariance_method.n_effective / static_cast<double>(n_draws);
  }
  const Eigen::MatrixXd centred = betas.colwise() - betas.rowwise().mean();
  mc.spread = (centred.rowwise().squaredNorm() / static_cast<double>(n_draws - 1)).cwiseSqrt().transpose();
  return mc;
}

// ρ = 0.8: the white σ is √(1.8/0.2) = 3 times too small; the batch-means σ
// within 15 % of the Monte Carlo spread (a draw's σ scatters by ~1/√(2B) =
// 7 % over B = 100 blocks, the mean over 400 draws by far less; the spread
// itself by ~3.5 %; the blocks' bias for ρ = 0.8 and L = 100 is −2 %). Three
// cases: OLS with the same noise on both joints; OLS with joint 2's three
// times joint 1's (the white formula pools them, so only the batch-means σ
// is checked); WLS with that noise (weights 1/σ_j undo it, so the white σ is
// again off by the AR(1) factor alone).
TEST(ResidualCovarianceTest, Ar1NoiseBatchMeansSigmaMatchesTheMonteCarloSpread) {
  const double rho = 0.8;
  const double factor = std::sqrt((1.0 + rho) / (1.0 - rho));
  const double n_eff_ar1 = 10000 * (1.0 - rho) / (1.0 + rho);
  struct Case { bool wls; double sd2; bool white_by_factor; };
  for (const Case c : {Case{false, 1.0, true}, Case{false, 3.0, false}, Case{true, 3.0, true}}) {
    const MonteCarlo mc = RunMonteCarlo(rho, c.wls, c.sd2);
    const Eigen::ArrayXd hac_ratio = mc.mean_sigma.array() / mc.spread.array();
    const Eigen::ArrayXd white_ratio = mc.mean_white.array() / mc.spread.array();
    std::printf("%s, joint sd 1 and %.0f, rho %.2f: sigma/spread batch means %s, white %s (AR(1): 1/%.3g = %.3g); "
                "n_eff %.0f of 10000 (AR(1): n (1-rho)/(1+rho) = %.0f)\n",
                c.wls ? "WLS" : "OLS", c.sd2, rho, RatioText(hac_ratio).c_str(), RatioText(white_ratio).c_str(), factor,
                1.0 / factor, mc.mean_n_effective, n_eff_ar1);
    for (int k = 0; k < kParameters; ++k) {
      EXPECT_NEAR(hac_ratio[k], 1.0, 0.15) << "parameter " << k << (c.wls ? " (WLS)" : " (OLS)") << " sd2 " << c.sd2;
      // The white σ is off by the AR(1) factor (to the Monte Carlo's 3.5 %
      // and the regressors' slow variation).
      if (c.white_by_factor) EXPECT_NEAR(white_ratio[k] * factor, 1.0, 0.15) << "parameter " << k;
    }
    if (c.white_by_factor) EXPECT_NEAR(mc.mean_n_effective / n_eff_ar1, 1.0, 0.2);
    // Andrews' length for ρ = 0.8 is 67 samples: the blocks stay at √n.
    EXPECT_EQ(mc.min_block, 100);
    EXPECT_EQ(mc.max_block, 100);
  }
}

// ρ = 0.97 (a correlation time of 33 samples): blocks of √n = 100 samples
// leave out the correlation across their boundaries, 2 Σ ℓ ρ^ℓ / L of the
// long-run variance, σ (1 − 0.33)^½ = 0.82 of the truth; Andrews' length
// (L_A = 1.1447 (α n)^⅓ = 253, α = 4ρ²/((1 − ρ)²(1 + ρ)²)) takes the next
// summed length, 400 samples (25 blocks): σ within (1 − 0.08)^½ = 0.96, to
// the σ's own scatter (~1/√(2·25) = 14 % per draw, 0.7 % over 400 draws).
TEST(ResidualCovarianceTest, StronglyCorrelatedNoiseTakesLongerBlocks) {
  const double rho = 0.97;
  const MonteCarlo fixed = RunMonteCarlo(rho, false, 1.0, 400, 10000, 100);
  const MonteCarlo chosen = RunMonteCarlo(rho, false, 1.0, 400, 10000);
  const Eigen::ArrayXd fixed_ratio = fixed.mean_sigma.array() / fixed.spread.array();
  const Eigen::ArrayXd chosen_ratio = chosen.mean_sigma.array() / chosen.spread.array();
  std::printf("rho 0.97: sigma/spread with blocks of 100: %s; chosen (%ld to %ld samples): %s\n",
              RatioText(fixed_ratio).c_str(), static_cast<long>(chosen.min_block), static_cast<long>(chosen.max_block),
              RatioText(chosen_ratio).c_str());
  EXPECT_EQ(chosen.min_block, 400);
  EXPECT_EQ(chosen.max_block, 400);
  for (int k = 0; k < kParameters; ++k) {
    EXPECT_LT(fixed_ratio[k], 0.9) << "parameter " << k;  // the √n blocks' shortfall (0.82 expected)
    EXPECT_NEAR(chosen_ratio[k], 0.96, 0.08) << "parameter " << k;
  }
}

// White noise: the batch-means σ is the white σ, to its own scatter, where
// the white formula holds (one noise level, or WLS); with joint 2's noise
// three times joint 1's, OLS's white σ is wrong and the batch-means σ still
// matches the Monte Carlo spread.
TEST(ResidualCovarianceTest, WhiteNoiseBatchMeansSigmaIsTheWhiteSigma) {
  struct Case { bool wls; double sd2; };
  for (const Case c : {Case{false, 1.0}, Case{true, 3.0}, Case{false, 3.0}}) {
    const MonteCarlo mc = RunMonteCarlo(0.0, c.wls, c.sd2);
    const Eigen::ArrayXd hac_ratio = mc.mean_sigma.array() / mc.spread.array();
    const Eigen::ArrayXd to_white = mc.mean_sigma.array() / mc.mean_white.array();
    std::printf("%s, joint sd 1 and %.0f, white noise: sigma/spread batch means %s; batch means / white %s; n_eff %.0f "
                "of 10000\n", c.wls ? "WLS" : "OLS", c.sd2, RatioText(hac_ratio).c_str(), RatioText(to_white).c_str(),
                mc.mean_n_effective);
    for (int k = 0; k < kParameters; ++k) {
      EXPECT_NEAR(hac_ratio[k], 1.0, 0.15) << "parameter " << k;
      // The mean of 400 draws: ~0.4 % scatter, bias ≲ 1/B.
      if (c.wls || c.sd2 == 1.0) EXPECT_NEAR(to_white[k], 1.0, 0.05) << "parameter " << k;
    }
    if (c.wls || c.sd2 == 1.0) EXPECT_NEAR(mc.mean_n_effective / 10000.0, 1.0, 0.1);
  }
}

// Σ_b S_b S_bᵀ by hand on a few scores, with a shorter last block, and
// B/(B − 1); the block length ⌈√n⌉.
TEST(ResidualCovarianceTest, BlockSumsByHand) {
  EXPECT_EQ(BatchMeansBlockSamples(1), 1);
  EXPECT_EQ(BatchMeansBlockSamples(4), 2);
  EXPECT_EQ(BatchMeansBlockSamples(5), 3);
  EXPECT_EQ(BatchMeansBlockSamples(5027), 71);
  EXPECT_EQ(BatchMeansBlockSamples(10000), 100);
  // Lengths summed: ⌈√n⌉ doubled while kMinAutoBlocks blocks remain.
  ScoreBatchMeans automatic(1, 10000);
  for (int t = 0; t < 10000; ++t) automatic.Push(Eigen::VectorXd::Constant(1, t % 2 ? 1.0 : -1.0));
  EXPECT_EQ(automatic.andrews_block_samples(), 0.0);  // ρ = −1 counts as 0
  EXPECT_EQ(automatic.block_samples(), 100);
  ScoreBatchMeans slow(1, 10000);  // ρ → 1: the longest length, 400 (25 blocks; 800 would leave 12)
  for (int t = 0; t < 10000; ++t) slow.Push(Eigen::VectorXd::Constant(1, t < 5000 ? 1.0 : -1.0));
  EXPECT_GT(slow.andrews_block_samples(), 400.0);
  EXPECT_EQ(slow.block_samples(), 400);
  EXPECT_EQ(slow.n_blocks(), 25);
  ScoreBatchMeans scores(2, 5, 2);
  const std::vector<Eigen::Vector2d> s = {{1, 2}, {3, -1}, {0.5, 0.5}, {-2, 1}, {4, 0}};
  for (const Eigen::Vector2d& x : s) scores.Push(x);
  EXPECT_TRUE(scores.done());
  EXPECT_EQ(scores.n_blocks(), 3);
  const Eigen::Vector2d S0 = s[0] + s[1], S1 = s[2] + s[3], S2 = s[4];
  const Eigen::Matrix2d expected = 1.5 * (S0 * S0.transpose() + S1 * S1.transpose() + S2 * S2.transpose());
  EXPECT_LT((scores.Omega() - expected).norm(), 1e-14 * expected.norm());
  EXPECT_THROW(scores.Push(Eigen::Vector2d(1, 1)), std::invalid_argument);
  EXPECT_THROW(ScoreBatchMeans(0, 5), std::invalid_argument);
  ScoreBatchMeans short_of(2, 5);
  short_of.Push(Eigen::Vector2d(1, 1));
  EXPECT_THROW(short_of.Omega(), std::invalid_argument);
}

// Several logs fitted together (identify --data A --data B): EndSeries
// closes the block being filled, so no block straddles two logs; by hand on
// series of 3 and 4 scores in blocks of 2: {s0 s1} {s2} | {s3 s4} {s5 s6}
// (without the break: {s0 s1} {s2 s3} {s4 s5} {s6}). The lag-1 sum does not
// pair s3 with s2: a series of +1 then one of −1 scores has ρ = 1 within
// each, and Andrews' length is that of ρ → 1, not lowered by the jump.
TEST(ResidualCovarianceTest, EndSeriesKeepsBlocksWithinALog) {
  const std::vector<Eigen::Vector2d> s = {{1, 2}, {3, -1}, {0.5, 0.5}, {-2, 1}, {4, 0}, {1, 1}, {-1, 3}};
  ScoreBatchMeans scores(2, 7, 2);
  for (int t = 0; t < 3; ++t) scores.Push(s[static_cast<size_t>(t)]);
  scores.EndSeries();
  scores.EndSeries();  // at a block's end: nothing more
  for (int t = 3; t < 7; ++t) scores.Push(s[static_cast<size_t>(t)]);
  ASSERT_TRUE(scores.done());
  EXPECT_EQ(scores.n_blocks(), 4);
  const Eigen::Vector2d S0 = s[0] + s[1], S1 = s[2], S2 = s[3] + s[4], S3 = s[5] + s[6];
  const Eigen::Matrix2d expected =
      4.0 / 3.0 * (S0 * S0.transpose() + S1 * S1.transpose() + S2 * S2.transpose() + S3 * S3.transpose());
  EXPECT_LT((scores.Omega() - expected).norm(), 1e-14 * expected.norm());

  ScoreBatchMeans two_logs(1, 200), one_log(1, 200);
  for (int t = 0; t < 200; ++t) {
    if (t == 100) two_logs.EndSeries();
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, t < 100 ? 1.0 : -1.0);
    two_logs.Push(x);
    one_log.Push(x);
  }
  // ρ = Σ s_t s_{t−1} / Σ s_t²: 198/200 without the pair across the break, 197/200 with it.
  const double rho_two = 198.0 / 200.0, rho_one = 197.0 / 200.0;
  auto andrews = [](double rho) {
    return 1.1447 * std::cbrt(4.0 * rho * rho / std::pow((1 - rho) * (1 + rho), 2) * 200.0);
  };
  EXPECT_NEAR(two_logs.andrews_block_samples(), andrews(rho_two), 1e-9 * andrews(rho_two));
  EXPECT_NEAR(one_log.andrews_block_samples(), andrews(rho_one), 1e-9 * andrews(rho_one));
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// The instrumental-variables sandwich (StackedInstrumentSandwich) against a
// Monte Carlo: τ = W β + e with AR(1) noise (ρ = 0.8) on both joints, W the
// slow regressor observed with white noise of its own (Wn = W + U, the
// regressor an estimator sees), instruments Z = W (noise-free, as a re-simulation gives),
// β̂ = (ZᵀWn)⁻¹ Zᵀ τ. Its σ over 300 draws matches the spread of β̂ within
// 15 %, where the white formula is off by the AR(1) factor √((1 + ρ)/(1 − ρ)) = 3.
// With Z = W and no regressor noise it is least squares' sandwich exactly.
TEST(ResidualCovarianceTest, InstrumentSandwichMatchesTheMonteCarloSpread) {
  const Eigen::Index n = 10000;
  const Eigen::MatrixXd W = SlowRegressor(n);
  const Eigen::Vector4d beta(1.0, -2.0, 0.5, 3.0);
  const double rho = 0.8, innovation = std::sqrt(1.0 - rho * rho);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int n_draws = 300;
  Eigen::MatrixXd estimates(n_draws, kParameters), sigmas(n_draws, kParameters), whites(n_draws, kParameters);
  for (int d = 0; d < n_draws; ++d) {
    Eigen::VectorXd tau = W * beta;
    Eigen::Vector2d e(normal(rng), normal(rng));
    for (Eigen::Index s = 0; s < n; ++s) {
      if (s > 0) e = rho * e + innovation * Eigen::Vector2d(normal(rng), normal(rng));
      tau.segment<2>(kDof * s) += e;
    }
    Eigen::MatrixXd Wn = W;
    for (Eigen::Index r = 0; r < Wn.rows(); ++r)
      for (int c = 0; c < kParameters; ++c) Wn(r, c) += 0.05 * normal(rng);
    const Eigen::MatrixXd B = (W.transpose() * Wn).inverse();
    const Eigen::VectorXd beta_hat = B * W.transpose() * tau;
    const Eigen::VectorXd r = tau - Wn * beta_hat;
    const double s2 = r.squaredNorm() / static_cast<double>(r.size() - kParameters);
    const Eigen::MatrixXd white = s2 * B * (W.transpose() * W) * B.transpose();
    const Eigen::MatrixXd cov = StackedInstrumentSandwich(W, r, kDof, B, white, nullptr);
    estimates.row(d) = beta_hat.transpose();
    sigmas.row(d) = cov.diagonal().cwiseSqrt().transpose();
    whites.row(d) = white.diagonal().cwiseSqrt().transpose();
  }
  const Eigen::RowVectorXd mean = estimates.colwise().mean();
  const Eigen::ArrayXd spread =
      ((estimates.rowwise() - mean).colwise().squaredNorm() / (n_draws - 1)).cwiseSqrt().transpose().array();
  const Eigen::ArrayXd ratio = sigmas.colwise().mean().transpose().array() / spread;
  const Eigen::ArrayXd white_ratio = whites.colwise().mean().transpose().array() / spread;
  std::printf("IV, rho 0.8: sigma/spread batch means %s, white %s\n", RatioText(ratio).c_str(),
              RatioText(white_ratio).c_str());
  for (int k = 0; k < kParameters; ++k) {
    EXPECT_NEAR(ratio[k], 1.0, 0.15) << "parameter " << k;
    EXPECT_NEAR(white_ratio[k] * 3.0, 1.0, 0.2) << "parameter " << k;
  }

  // Z = W, no regressor noise: B = (WᵀW)⁻¹, the least-squares sandwich.
  const Eigen::VectorXd tau = W * beta + Eigen::VectorXd::NullaryExpr(W.rows(), [&] { return normal(rng); });
  const Eigen::MatrixXd G = (W.transpose() * W).inverse();
  const Eigen::VectorXd r = tau - W * (G * W.transpose() * tau);
  const Eigen::MatrixXd ls = StackedSandwichCovariance(W, r, kDof, G, 1.0, nullptr);
  const Eigen::MatrixXd iv = StackedInstrumentSandwich(W, r, kDof, G, G, nullptr);
  EXPECT_LT((iv - ls).norm(), 1e-12 * ls.norm());
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// Scores whose spectrum nearly vanishes at zero frequency, as the residual of
// the closed-loop estimators (the loop's reaction to the position noise):
// s_t = u_t + c (d_t − d_{t−1}), u and d white of variance 1, so that the
// differences telescope and the true Ω = Var(Σ_t s_t) = n (+ 2c², nothing per
// sample). A block of L sums to Σ u + c (d_end − d_before): batch means give
// n (1 + 2c²/L), here with c = 10 and ⌈√n⌉ = 100 (Andrews' rule sees ρ < 0
// and keeps it) 3 n, while the extrapolation from 200 and 400 removes the
// 1/L term: f Ω(400) with E Ω(L) = n (1 + 200/L) and f = 2 − 2/1.5 gives n.
// Nine components (f is their median, as over a robot's base parameters);
// the mean over 100 draws and the components of Ω_kk / n (each estimate has a
// relative spread of about √(2/25) = 0.28 over 25 blocks, the factor's adds
// to it).
TEST(ResidualCovarianceTest, ExtrapolatedBlockBiasRemovesTheOneOverLTermOfTelescopingScores) {
  constexpr Eigen::Index kN = 10000;
  constexpr int kDraws = 100, kComponents = 9;
  constexpr double kC = 10.0;
  std::mt19937_64 rng(37);
  std::normal_distribution<double> normal;
  auto draw_vector = [&] {
    Eigen::VectorXd x(kComponents);
    for (int k = 0; k < kComponents; ++k) x[k] = normal(rng);
    return x;
  };
  double mean_as_is = 0.0, mean_extrapolated = 0.0, min_factor = 2.0, max_factor = 0.0;
  for (int draw = 0; draw < kDraws; ++draw) {
    ScoreBatchMeans as_is(kComponents, kN), extrapolated(kComponents, kN, 0, BlockBias::kExtrapolated);
    Eigen::VectorXd d_before = draw_vector();
    for (Eigen::Index t = 0; t < kN; ++t) {
      const Eigen::VectorXd u = draw_vector(), d = draw_vector();
      const Eigen::VectorXd s = u + kC * (d - d_before);
      d_before = d;
      as_is.Push(s);
      extrapolated.Push(s);
    }
    ASSERT_EQ(as_is.block_samples(), 100);
    ASSERT_EQ(extrapolated.block_samples(), 400);
    ASSERT_EQ(extrapolated.n_blocks(), 25);
    EXPECT_EQ(as_is.block_bias_factor(), 1.0);
    min_factor = std::min(min_factor, extrapolated.block_bias_factor());
    max_factor = std::max(max_factor, extrapolated.block_bias_factor());
    mean_as_is += as_is.Omega().diagonal().mean() / (kN * kDraws);
    mean_extrapolated += extrapolated.Omega().diagonal().mean() / (kN * kDraws);
  }
  std::printf("telescoping scores: Ω_kk / n as is %.3f, extrapolated %.3f (f %.3f to %.3f)\n", mean_as_is,
              mean_extrapolated, min_factor, max_factor);
  EXPECT_NEAR(mean_as_is, 3.0, 0.15);  // the old estimate: three times the truth
  // f is larger where Ω(2L) is (both from the same blocks): about +9 % here.
  EXPECT_GT(mean_extrapolated, 0.9);
  EXPECT_LT(mean_extrapolated, 1.2);
  EXPECT_GT(min_factor, 0.1);  // never at the clamp here
  EXPECT_LT(max_factor, 1.0);
}

// A given block length, or a log too short for two lengths, is not
// extrapolated: the same Ω as kAsIs.
TEST(ResidualCovarianceTest, ExtrapolatedBlockBiasNeedsTwoLengths) {
  ScoreBatchMeans given(1, 100, 10, BlockBias::kExtrapolated), given_as_is(1, 100, 10);
  ScoreBatchMeans short_log(1, 100, 0, BlockBias::kExtrapolated), short_as_is(1, 100);
  for (int t = 0; t < 100; ++t) {
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, std::sin(0.7 * t) + (t % 3 == 0 ? 1.0 : -0.5));
    for (ScoreBatchMeans* s : {&given, &given_as_is, &short_log, &short_as_is}) s->Push(x);
  }
  EXPECT_EQ(given.block_bias_factor(), 1.0);
  EXPECT_EQ(short_log.block_bias_factor(), 1.0);
  EXPECT_EQ(given.Omega()(0, 0), given_as_is.Omega()(0, 0));
  EXPECT_EQ(short_log.Omega()(0, 0), short_as_is.Omega()(0, 0));
}

}  // namespace
}  // namespace idbench
