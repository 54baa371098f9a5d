#include "idbench/ident/streamed_joint_equations.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <stdexcept>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

// Settings with the filter and sample count given, the rest default.
StreamedEquationsSettings Settings(std::optional<ParallelFilter> filter, Eigen::Index n_samples) {
  StreamedEquationsSettings settings;
  settings.filter = std::move(filter);
  settings.n_samples = n_samples;
  return settings;
}

// A puma560 log at 1 kHz along the general motion, shaped like a
// controller's: t, q, measured qd, τ (no qdd), with noise on q, qd and τ.
class StreamedJointEquationsTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePuma560();
  FrictionModel friction_{.viscous = true, .coulomb = true, .rotor_inertia = true};
  BaseParameters base_ = ComputeBaseParameters(model_, friction_);
  JointLog recorded_ = [this] {
    const Eigen::Index n = 9001;  // 9 s
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 9.0});
    JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(n, 0.0, 9.0));
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < 6; ++j) {
        log.q(s, j) += 1e-4 * noise(rng);
        log.qd(s, j) += 1e-2 * noise(rng);
        log.tau(s, j) += 0.5 * noise(rng);
      }
    }
    log.qdd.resize(0, 0);
    return log;
  }();
  ParallelFilter filter_{.filter = {.order = 4, .cutoff_hz = 10.0, .decimation = 3, .trim_s = -1.0},
                         .sample_rate_hz = 1000.0};

  // The whole-log path: ProcessJointLog, then W and τ stacked and
  // parallel-filtered whole (StackEquations), solved dense.
  LinearFit WholeLogOls(const JointLog& log) const {
    LogFilterOptions derivatives = filter_.filter;
    derivatives.decimation = 1;
    derivatives.trim_s = 0.0;
    derivatives.filter_tau = false;
    const JointLog prepared = ProcessJointLog(log, derivatives);
    Eigen::MatrixXd W;
    Eigen::VectorXd tau;
    StackEquations(model_, friction_, base_, prepared, filter_, &W, &tau);
    return SolveOls(W, tau, 6);
  }
  // StreamedLogFilter, then the equations, in blocks of `block` samples fed
  // `push` samples at a time.
  StackedFactors Streamed(const JointLog& log, Eigen::Index block, Eigen::Index push) const {
    const Eigen::Index n = log.n_samples();
    StreamedLogFilter prepare(filter_.filter, filter_.sample_rate_hz, log.qd.size() > 0, false, 6, n, block);
    StreamedEquationsSettings settings = Settings(filter_, n);
    settings.block = block;
    StreamedJointEquations equations(model_, friction_, base_, settings);
    for (Eigen::Index s = 0; s < n; s += push) {
      prepare.Push(Rows(log, s, std::min<Eigen::Index>(push, n - s)),
                   [&](const JointLog& prepared, Eigen::Index) { equations.Push(prepared); });
    }
    EXPECT_TRUE(prepare.done());
    EXPECT_TRUE(equations.done());
    return equations.factors();
  }
  static JointLog Rows(const JointLog& log, Eigen::Index s, Eigen::Index m) {
    JointLog out;
    out.t = log.t.segment(s, m);
    for (auto [from, to] : {std::pair{&log.q, &out.q}, {&log.qd, &out.qd}, {&log.qdd, &out.qdd}, {&log.tau, &out.tau}}) {
      if (from->size() > 0) *to = from->middleRows(s, m);
    }
    return out;
  }
  static void ExpectSameFit(const LinearFit& streamed, const LinearFit& whole) {
    EXPECT_LT((streamed.beta - whole.beta).norm(), 1e-9 * whole.beta.norm());
    EXPECT_LT((streamed.sigma - whole.sigma).cwiseQuotient(whole.sigma).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((streamed.joint_rms - whole.joint_rms).cwiseQuotient(whole.joint_rms).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_NEAR(streamed.cond, whole.cond, 1e-9 * whole.cond);
  }
};

// Blocks smaller than the filter's margin (~1400 samples), pushes that leave
// one sample for the last, one block for the whole log: all equal the
// whole-log estimate (dense least squares on the whole W) to 1e-9.
TEST_F(StreamedJointEquationsTest, EqualsTheWholeLogPathAtAwkwardChunkSizes) {
  const LinearFit whole = WholeLogOls(recorded_);
  for (auto [block, push] : {std::pair<Eigen::Index, Eigen::Index>{500, 1000}, {2048, 3000}, {4000, 9000}, {9001, 777},
                             {kStreamBlockSamples, 9000}}) {
    SCOPED_TRACE("block " + std::to_string(block) + ", push " + std::to_string(push));
    const StackedFactors factors = Streamed(recorded_, block, push);
    EXPECT_EQ(factors.n_samples(), (9001 - 2 * 500 + 2) / 3);  // 5/fc = 500 samples trimmed, every 3rd kept
    ExpectSameFit(SolveOls(factors), whole);
  }
}

// A log of q and τ only: qd and qdd from the filtered q.
TEST_F(StreamedJointEquationsTest, EqualsTheWholeLogPathFromPositionsOnly) {
  JointLog positions = recorded_;
  positions.qd.resize(0, 0);
  ExpectSameFit(SolveOls(Streamed(positions, 1000, 4000)), WholeLogOls(positions));
}

// Without a filter (qd, qdd recorded) every sample is folded, as by
// FactorStackedEquations; the bounded outputs are every k-th sample.
TEST_F(StreamedJointEquationsTest, WithoutFilterFoldsEverySampleAndKeepsBoundedSeries) {
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 3.0});
  JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(3001, 0.0, 3.0));
  log.tau += 0.5 * Eigen::MatrixXd::Random(3001, 6);  // residuals well above rounding
  const Eigen::VectorXd beta = Eigen::VectorXd::LinSpaced(base_.n_base(), 0.5, 1.5);
  StreamedEquationsSettings settings = Settings(std::nullopt, 3001);
  settings.series_beta = beta;
  settings.series_stride = 7;
  StreamedJointEquations equations(model_, friction_, base_, settings);
  for (Eigen::Index s = 0; s < 3001; s += 1000) equations.Push(Rows(log, s, std::min<Eigen::Index>(1000, 3001 - s)));
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model_, friction_, base_, log, std::nullopt, &W, &tau);
  ExpectSameFit(SolveOls(equations.factors()), SolveOls(W, tau, 6));
  const TorqueSeries& series = equations.series();
  ASSERT_EQ(series.t.size(), 429);  // ⌈3001/7⌉
  const Eigen::VectorXd predicted = W.middleRows(6 * 7 * 428, 6) * beta;
  EXPECT_EQ(series.t[428], log.t[7 * 428]);
  EXPECT_LT((series.predicted.row(428).transpose() - predicted).norm(), 1e-12 * predicted.norm());
  EXPECT_EQ(series.measured.row(428), log.tau.row(7 * 428));
}

// The second pass for σ (score_fit, no fold): the batch-means covariance of
// the streamed scores equals that of the scores of the whole parallel-filtered
// W (PushStackedScores) to 1e-9, for WLS (weighted scores), blocks of the
// stream smaller than the filter's margin.
TEST_F(StreamedJointEquationsTest, SecondPassScoresEqualTheWholeLogScores) {
  LinearFit streamed = SolveWls(Streamed(recorded_, 1000, 4000));
  // The whole-log W, as WholeLogOls builds it.
  LogFilterOptions derivatives = filter_.filter;
  derivatives.decimation = 1;
  derivatives.trim_s = 0.0;
  derivatives.filter_tau = false;
  const JointLog prepared = ProcessJointLog(recorded_, derivatives);
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model_, friction_, base_, prepared, filter_, &W, &tau);
  LinearFit whole = SolveWls(W, tau, 6);
  ApplyStackedScoreCovariance(W, tau, 6, &whole);

  const Eigen::Index n = recorded_.n_samples();
  StreamedLogFilter prepare(filter_.filter, filter_.sample_rate_hz, true, false, 6, n, 1000);
  StreamedEquationsSettings settings = Settings(filter_, n);
  settings.block = 1000;
  settings.score_fit = &streamed;
  settings.fold = false;
  StreamedJointEquations equations(model_, friction_, base_, settings);
  for (Eigen::Index s = 0; s < n; s += 4000) {
    prepare.Push(Rows(recorded_, s, std::min<Eigen::Index>(4000, n - s)),
                 [&](const JointLog& samples, Eigen::Index) { equations.Push(samples); });
  }
  ASSERT_NE(equations.scores(), nullptr);
  EXPECT_TRUE(equations.scores()->done());
  EXPECT_EQ(equations.factors().n_samples(), 0);  // not folded
  ApplyScoreCovariance(*equations.scores(), &streamed);
  EXPECT_EQ(streamed.covariance_method.n_blocks, whole.covariance_method.n_blocks);
  EXPECT_LT((streamed.sigma - whole.sigma).cwiseQuotient(whole.sigma).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(streamed.covariance_method.n_effective, whole.covariance_method.n_effective,
              1e-9 * whole.covariance_method.n_effective);
  // The filtered equations' residual is coloured: σ above the white one.
  EXPECT_GT(streamed.covariance_method.n_effective, 0.0);
  EXPECT_LT(streamed.covariance_method.n_effective, 0.9 * static_cast<double>(streamed.covariance_method.n_samples));
}

TEST_F(StreamedJointEquationsTest, RejectsTooManySamplesAndTooShortLogs) {
  StreamedJointEquations equations(model_, friction_, base_, Settings(filter_, 2000));
  JointLog prepared = Rows(recorded_, 0, 2001);
  prepared.qdd = prepared.qd;
  EXPECT_THROW(equations.Push(prepared), std::invalid_argument);
  EXPECT_THROW(equations.Push(Rows(recorded_, 0, 10)), std::invalid_argument);  // no qdd
  EXPECT_THROW(StreamedJointEquations(model_, friction_, base_, Settings(filter_, 1000)),
               std::invalid_argument);  // 2 × 500 samples trimmed
}

}  // namespace
}  // namespace idbench
