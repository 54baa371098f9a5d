#include "idbench/ident/linear_estimator.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <random>

#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/simulation.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"

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

TEST(LinearEstimatorTest, ClassifiesParametersBySigma) {
  EXPECT_EQ(ClassifyParameter(1.0, 0.05), ParameterStatus::kDetermined);
  EXPECT_EQ(ClassifyParameter(-2.0, 0.2), ParameterStatus::kDetermined);  // 10 %: the boundary
  EXPECT_EQ(ClassifyParameter(1.0, 0.2), ParameterStatus::kPoor);
  EXPECT_EQ(ClassifyParameter(-1.0, 0.3), ParameterStatus::kPoor);
  EXPECT_EQ(ClassifyParameter(1.0, 1.0 / 3.0), ParameterStatus::kIndistinguishableFromZero);
  EXPECT_EQ(ClassifyParameter(0.0, 1e-6), ParameterStatus::kIndistinguishableFromZero);
  EXPECT_EQ(ClassifyParameter(0.0, 0.0), ParameterStatus::kDetermined);
  EXPECT_EQ(ClassifyParameter(1.0, std::nan("")), ParameterStatus::kNotIdentifiable);
  EXPECT_EQ(ClassifyParameter(1.0, std::numeric_limits<double>::infinity()), ParameterStatus::kNotIdentifiable);
}

TEST(LinearEstimatorTest, RejectsTooFewEquations) {
  EXPECT_THROW(SolveOls(Eigen::MatrixXd::Zero(6, 10), Eigen::VectorXd::Zero(6), 6), std::invalid_argument);
  EXPECT_THROW(SolveOls(Eigen::MatrixXd::Zero(12, 2), Eigen::VectorXd::Zero(11), 6), std::invalid_argument);
}

// The textbook computation on the whole stacked matrix, independent of the
// per-joint factors: rows of joint j scaled by weights[j], one dense
// Householder QR, cov = s² R⁻¹R⁻ᵀ, cond(W) from the SVD of W itself,
// residuals (unweighted) from W β − τ.
struct DenseFit {
  Eigen::VectorXd beta, sigma, joint_rms;
  double cond = 0.0;
};
DenseFit DenseReference(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, const Eigen::VectorXd& weights) {
  const int n_dof = static_cast<int>(weights.size());
  Eigen::MatrixXd Ww = W;
  Eigen::VectorXd tw = tau;
  for (Eigen::Index r = 0; r < W.rows(); ++r) {
    Ww.row(r) *= weights[r % n_dof];
    tw[r] *= weights[r % n_dof];
  }
  const Eigen::Index p = W.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Ww);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  DenseFit fit;
  fit.beta = R.triangularView<Eigen::Upper>().solve((qr.householderQ().transpose() * tw).head(p));
  const double s2 = (Ww * fit.beta - tw).squaredNorm() / static_cast<double>(W.rows() - p);
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  fit.sigma = ((Rinv * Rinv.transpose()).diagonal() * s2).cwiseSqrt();
  const Eigen::VectorXd s = Eigen::BDCSVD<Eigen::MatrixXd>(Ww).singularValues();
  fit.cond = s[0] / s[s.size() - 1];
  fit.joint_rms = JointRms(W * fit.beta - tau, n_dof);
  return fit;
}

void ExpectSameFit(const LinearFit& fit, const DenseFit& dense) {
  EXPECT_LT(testing::RelativeError(fit.beta, dense.beta), 1e-10);
  EXPECT_LT(testing::RelativeError(fit.sigma, dense.sigma), 1e-10);
  EXPECT_LT(testing::RelativeError(fit.joint_rms, dense.joint_rms), 1e-10);
  EXPECT_NEAR(fit.cond / dense.cond, 1.0, 1e-10);
}

// Streamed, per-joint, multi-threaded stacking + OLS/WLS agrees with the dense
// QR of the whole stacked W, on puma560 (Fv, Fc: 48 base parameters), 10 000
// random states (three factor parts) and noisy torques; and does not depend
// on the number of threads.
TEST(LinearEstimatorTest, StreamedFactorsMatchDenseQr) {
  const RobotModel model = MakePuma560();
  FrictionModel friction;
  friction.viscous = friction.coulomb = true;
  const BaseParameters base = ComputeBaseParameters(model, friction);
  ASSERT_EQ(base.n_base(), 48);
  const int n_samples = 10000;
  ASSERT_GT(n_samples, 2 * kSamplesPerFactorPart);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::normal_distribution<double> normal;
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n_samples, 0.0, 1e-3 * (n_samples - 1));
  log.q = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return 1.5 * u(rng); });
  log.qd = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return u(rng); });
  log.qdd = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return 2.0 * u(rng); });
  log.tau = Eigen::MatrixXd::Zero(n_samples, 6);  // set below from W
  const Eigen::MatrixXd W = StackBaseRegressor(model, friction, base, log);
  const Eigen::VectorXd beta_model = base.combination * StandardParameters(model, friction);
  const Eigen::VectorXd noise_sigma = (Eigen::VectorXd(6) << 0.5, 0.5, 0.5, 0.05, 0.05, 0.05).finished();
  Eigen::VectorXd tau = W * beta_model;
  for (Eigen::Index r = 0; r < tau.size(); ++r) tau[r] += noise_sigma[r % 6] * normal(rng);
  log.tau = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      tau.data(), n_samples, 6);
  ASSERT_EQ(StackTorques(log), tau);

  const DenseFit dense_ols = DenseReference(W, tau, Eigen::VectorXd::Ones(6));
  // WLS weights: per-joint OLS residual variance with the degrees of freedom shared among joints.
  const double per_joint_dof = (6.0 * n_samples - 48.0) / 6.0;
  const Eigen::VectorXd joint_sigma = dense_ols.joint_rms * std::sqrt(n_samples / per_joint_dof);
  const DenseFit dense_wls = DenseReference(W, tau, joint_sigma.cwiseInverse());

  const StackedFactors one_thread = FactorStackedEquations(model, friction, base, log, 1);
  EXPECT_EQ(one_thread.n_samples(), n_samples);
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    const StackedFactors factors = FactorStackedEquations(model, friction, base, log, threads);
    const LinearFit ols = SolveOls(factors);
    ExpectSameFit(ols, dense_ols);
    const LinearFit wls = SolveWls(factors);
    ExpectSameFit(wls, dense_wls);
    EXPECT_LT(testing::RelativeError(wls.joint_sigma, joint_sigma), 1e-10);
    // Fixed parts merged in a fixed order: bit-identical whatever the thread count.
    for (int j = 0; j < 6; ++j) EXPECT_EQ(factors.joints[j].T, one_thread.joints[j].T) << "joint " << j + 1;
  }
  // Variance inflation: (WᵀW)⁻¹_kk ‖W_k‖², from W itself.
  const Eigen::MatrixXd gram_inverse = (W.transpose() * W).inverse();
  const Eigen::VectorXd vif = gram_inverse.diagonal().cwiseProduct(W.colwise().squaredNorm().transpose());
  EXPECT_LT(testing::RelativeError(SolveOls(one_thread).variance_inflation, vif), 1e-9);
  EXPECT_GE(vif.minCoeff(), 1.0);
  // Residuals of any β from the factors: per joint, and all joints weighted in
  // one factor (what the physically consistent fit minimises).
  const Eigen::VectorXd beta = beta_model + 0.1 * testing::RandomVector(48, 1.0, &rng);
  const Eigen::VectorXd r = W * beta - tau;
  const Eigen::VectorXd joint_norms = JointRms(r, 6) * std::sqrt(static_cast<double>(n_samples));
  EXPECT_LT(testing::RelativeError(JointResidualNorms(one_thread, beta), joint_norms), 1e-12);
  const Eigen::MatrixXd combined = CombinedFactor(one_thread, joint_sigma.cwiseInverse());
  EXPECT_TRUE(combined.isUpperTriangular(0.0));
  const double weighted = (combined.topLeftCorner(48, 48) * beta - combined.col(48).head(48)).squaredNorm() +
                          combined(48, 48) * combined(48, 48);
  EXPECT_NEAR(weighted, joint_norms.cwiseQuotient(joint_sigma).squaredNorm(), 1e-12 * weighted);
  EXPECT_THROW(CombinedFactor(one_thread, Eigen::VectorXd::Ones(5)), std::invalid_argument);
  EXPECT_THROW(JointResidualNorms(one_thread, beta.head(47)), std::invalid_argument);
  // The dense entry points (factors of the given W) agree too.
  ExpectSameFit(SolveOls(W, tau, 6), dense_ols);
  ExpectSameFit(SolveWls(W, tau, 6), dense_wls);
  // The noise is what the model says: the estimate is within a few σ of the truth.
  EXPECT_LT(((dense_ols.beta - beta_model).cwiseQuotient(dense_ols.sigma)).cwiseAbs().maxCoeff(), 5.0);
}

// Folding rows into a factor in blocks gives the R factor of all rows: RᵀR = AᵀA.
// 5 columns fit in one panel of reflections; 21 take three (two blocked
// updates, a partial last panel), with an all-zero column among them; block
// sizes are not multiples of the vector width.
TEST(LinearEstimatorTest, FoldedFactorIsTheQrFactor) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {5, 21}) {
    SCOPED_TRACE("columns " + std::to_string(n));
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(50, n, [&] { return u(rng); });
    if (n > 10) A.col(9).setZero();
    std::vector<int> columns(static_cast<size_t>(n - 1));
    for (int k = 0; k < n - 1; ++k) columns[static_cast<size_t>(k)] = k;
    StackedFactors factors(n - 1, {columns});
    for (int r0 : {0, 7, 30}) {
      Eigen::MatrixXd rows = A.middleRows(r0, r0 == 0 ? 7 : r0 == 7 ? 23 : 20);
      FoldJointRows(rows, &factors.joints[0]);
    }
    const Eigen::MatrixXd& T = factors.joints[0].T;
    EXPECT_EQ(factors.joints[0].n_rows, 50);
    EXPECT_TRUE(T.isUpperTriangular(0.0));
    EXPECT_LT(testing::RelativeError(Eigen::MatrixXd(T.transpose() * T), Eigen::MatrixXd(A.transpose() * A)),
              1e-13);
  }
  StackedFactors factors(4, {{0, 1, 2, 3}});
  StackedFactors bad(4, {{0, 1, 2}});
  EXPECT_THROW(MergeStackedFactors(bad, &factors), std::invalid_argument);
  EXPECT_THROW(StackedFactors(4, {{1, 0}}), std::invalid_argument);
}

// A W that does not determine every parameter: columns 2 and 5 equal (only
// their sum is determined) and column 7 zero (a joint that does not move).
// Those three are flagged and get σ = ∞; the others equal the least squares
// of W without columns 5 and 7 (column 2 then carrying the sum); the solution
// near a prior takes the prior's split of the pair and its value of column 7.
TEST(LinearEstimatorTest, RankDeficientDataFlagTheParametersTheyDoNotDetermine) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  const int n_samples = 400, n_dof = 2, p = 9;
  Eigen::MatrixXd W = Eigen::MatrixXd::NullaryExpr(n_samples * n_dof, p, [&] { return normal(rng); });
  W.col(5) = W.col(2);
  W.col(7).setZero();
  const Eigen::VectorXd beta_true = testing::RandomVector(p, 2.0, &rng);
  Eigen::VectorXd tau = W * beta_true;
  for (Eigen::Index r = 0; r < tau.size(); ++r) tau[r] += 0.01 * normal(rng);
  const LinearFit fit = SolveOls(W, tau, n_dof);
  EXPECT_EQ(fit.rank, p - 2);
  EXPECT_TRUE(std::isinf(fit.cond));
  // Reference: the reduced problem, by dense QR.
  const std::vector<int> kept = {0, 1, 2, 3, 4, 6, 8};
  Eigen::MatrixXd W_kept(W.rows(), static_cast<Eigen::Index>(kept.size()));
  for (size_t c = 0; c < kept.size(); ++c) W_kept.col(static_cast<Eigen::Index>(c)) = W.col(kept[c]);
  const DenseFit reduced = DenseReference(W_kept, tau, Eigen::VectorXd::Ones(n_dof));
  for (size_t c = 0; c < kept.size(); ++c) {
    const int k = kept[c];
    SCOPED_TRACE(k);
    if (k == 2) {  // only the pair's sum
      EXPECT_FALSE(fit.identifiable[2]);
      EXPECT_NEAR(fit.beta[2] + fit.beta[5], reduced.beta[static_cast<Eigen::Index>(c)], 1e-10);
      continue;
    }
    EXPECT_TRUE(fit.identifiable[static_cast<size_t>(k)]);
    EXPECT_NEAR(fit.beta[k], reduced.beta[static_cast<Eigen::Index>(c)], 1e-10 * std::abs(fit.beta[k]) + 1e-12);
    EXPECT_NEAR(fit.sigma[k], reduced.sigma[static_cast<Eigen::Index>(c)], 1e-8 * fit.sigma[k]);
    EXPECT_EQ(ClassifyParameter(fit.beta[k], fit.sigma[k]) == ParameterStatus::kNotIdentifiable, false);
  }
  for (int k : {2, 5, 7}) {
    EXPECT_FALSE(fit.identifiable[static_cast<size_t>(k)]) << k;
    EXPECT_TRUE(std::isinf(fit.sigma[k])) << k;
    EXPECT_EQ(ClassifyParameter(fit.beta[k], fit.sigma[k]), ParameterStatus::kNotIdentifiable) << k;
  }
  EXPECT_LT(testing::RelativeError(fit.joint_rms, reduced.joint_rms), 1e-10);
}

}  // namespace
}  // namespace idbench
