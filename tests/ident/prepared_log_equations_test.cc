#include "idbench/ident/prepared_log_equations.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

// A puma560 controller log at 1 kHz (t, q, measured qd, τ with noise; no
// qdd) of 30 s: ~4 streaming blocks, the last one partial.
class PreparedLogEquationsTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePuma560();
  FrictionModel friction_{.viscous = true, .coulomb = true};
  BaseParameters base_ = ComputeBaseParameters(model_, friction_);
  JointLog full_ = [this] {
    const Eigen::Index n = 30001;
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 30.0});
    JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(n, 0.0, 30.0));
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < 6; ++j) {
        log.qd(s, j) += 1e-2 * noise(rng);
        log.tau(s, j) += 0.5 * noise(rng);
      }
    }
    return log;
  }();

  PreparedLog Prepare(JointLog log, const LogPreparationOptions& options) const {
    RecordedJointLog recorded;
    recorded.lines.resize(static_cast<size_t>(log.n_samples()));
    for (size_t s = 0; s < recorded.lines.size(); ++s) recorded.lines[s] = static_cast<int>(s) + 2;
    recorded.log = std::move(log);
    return PrepareRecordedJointLog(std::move(recorded), "log.csv", options);
  }
  static JointLog Window(const JointLog& log, Eigen::Index first, Eigen::Index n) {
    JointLog out;
    out.t = log.t.segment(first, n);
    for (auto [from, to] : {std::pair{&log.q, &out.q}, {&log.qd, &out.qd}, {&log.qdd, &out.qdd}, {&log.tau, &out.tau}}) {
      if (from->size() > 0) *to = from->middleRows(first, n);
    }
    return out;
  }
  static void ExpectSameFit(const LinearFit& streamed, const LinearFit& whole) {
    EXPECT_LT((streamed.beta - whole.beta).norm(), 1e-9 * whole.beta.norm());
    EXPECT_LT((streamed.sigma - whole.sigma).cwiseQuotient(whole.sigma).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((streamed.joint_rms - whole.joint_rms).cwiseQuotient(whole.joint_rms).cwiseAbs().maxCoeff(), 1e-9);
  }
};

// Filtered (qd recorded, qdd estimated), with a time window: the streamed
// factors solve to the dense whole-log estimate (ProcessJointLog on the
// window, W and τ stacked and parallel-filtered whole, one QR) to 1e-9; the
// held log is every k-th prepared sample when longer than max_held_samples.
TEST_F(PreparedLogEquationsTest, StreamedFitEqualsTheWholeLogFit) {
  JointLog recorded = full_;
  recorded.qdd.resize(0, 0);
  LogPreparationOptions options;
  options.time_window = {0.9995, 29.0005};  // samples 1000 to 29000
  options.filter.decimation = 2;
  options.max_held_samples = 10000;
  const PreparedLog prepared = Prepare(recorded, options);
  ASSERT_TRUE(prepared.parallel_filter);
  ASSERT_EQ(prepared.n_samples, 28001);
  EXPECT_EQ(prepared.log_stride, 3);
  ASSERT_EQ(prepared.log.n_samples(), 9334);

  const JointLog window = Window(recorded, 1000, 28001);
  LogFilterOptions derivatives = options.filter;
  derivatives.decimation = 1;
  derivatives.trim_s = 0.0;
  derivatives.filter_tau = false;
  const JointLog whole = ProcessJointLog(window, derivatives);
  EXPECT_LT((prepared.log.qdd.row(5000) - whole.qdd.row(15000)).norm(), 1e-9 * whole.qdd.row(15000).norm());
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model_, friction_, base_, whole, prepared.parallel_filter, &W, &tau);
  ExpectSameFit(SolveOls(FoldPreparedLog(prepared, model_, friction_, base_)), SolveOls(W, tau, 6));

  // The torque series: every kept equation, or every k-th beyond the bound.
  const Eigen::VectorXd beta = SolveOls(W, tau, 6).beta;
  TorqueSeries series;
  FoldPreparedLog(prepared, model_, friction_, base_, beta, &series, 5000);
  const Eigen::Index n_kept = W.rows() / 6, stride = (n_kept + 4999) / 5000;
  ASSERT_EQ(series.t.size(), (n_kept + stride - 1) / stride);
  const Eigen::VectorXd predicted = W.middleRows(6 * stride * 100, 6) * beta;
  EXPECT_LT((series.predicted.row(100).transpose() - predicted).norm(), 1e-9 * predicted.norm());
}

// qd and qdd recorded: no filter, every decimation-th sample of the window,
// as FactorStackedEquations on those samples.
TEST_F(PreparedLogEquationsTest, RecordedDerivativesAreDecimatedAndFolded) {
  LogPreparationOptions options;
  options.time_window = {0.4995, 20.0005};  // samples 500 to 20000
  options.filter.decimation = 3;
  const PreparedLog prepared = Prepare(full_, options);
  ASSERT_FALSE(prepared.parallel_filter);
  const JointLog window = Window(full_, 500, 19501);
  JointLog kept;
  kept.t = Decimate(window.t, 3);
  kept.q = Decimate(window.q, 3);
  kept.qd = Decimate(window.qd, 3);
  kept.qdd = Decimate(window.qdd, 3);
  kept.tau = Decimate(window.tau, 3);
  EXPECT_EQ(prepared.log.t, kept.t);
  EXPECT_EQ(prepared.log.tau, kept.tau);
  ExpectSameFit(SolveOls(FoldPreparedLog(prepared, model_, friction_, base_)),
                SolveOls(FactorStackedEquations(model_, friction_, base_, kept)));
}

// What holds a log whole (max_held_samples = 0) bounds it by max_samples: a
// longer log is refused after the counting pass, the message naming the log,
// its samples, the bound and the window (and, with qd and qdd recorded, the
// decimation) that fits; at the bound it is held whole.
TEST_F(PreparedLogEquationsTest, LogsBeyondMaxSamplesAreRefused) {
  LogPreparationOptions options;
  options.max_held_samples = 0;
  options.max_samples = 10000;
  auto refusal = [&](const JointLog& log) {
    try {
      Prepare(log, options);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  // qd, qdd recorded: 30001 samples at 1 kHz; decimation acts before holding.
  EXPECT_EQ(refusal(full_), "log.csv: 30001 samples to hold whole, more than 10000 (the bound that keeps memory from "
                            "growing with the log); choose a time_window of at most 9.999 s (10000 samples at 1000 Hz), "
                            "or a filter.decimation of at least 4");
  options.filter.decimation = 3;  // 10001 kept
  EXPECT_NE(refusal(full_).find("log.csv: 10001 samples to hold whole, more than 10000"), std::string::npos);
  options.filter.decimation = 4;  // 7501 kept, all held
  const PreparedLog decimated = Prepare(full_, options);
  EXPECT_EQ(decimated.n_samples, 7501);
  EXPECT_EQ(decimated.log.n_samples(), 7501);
  const Eigen::VectorXd kept_t = Decimate(full_.t, 4);
  EXPECT_EQ(decimated.log.t, kept_t);
  options.filter.decimation = 1;
  options.time_window = {0.4995, 10.4995};  // samples 500 to 10499: the bound
  const PreparedLog window = Prepare(full_, options);
  EXPECT_EQ(window.n_samples, 10000);
  EXPECT_EQ(window.log.tau, Window(full_, 500, 10000).tau);

  // qdd estimated: the filter's decimation acts on the samples held, so only
  // the window is named.
  JointLog filtered = full_;
  filtered.qdd.resize(0, 0);
  options.time_window.clear();
  options.filter.decimation = 2;
  EXPECT_EQ(refusal(filtered), "log.csv: 30001 samples to hold whole, more than 10000 (the bound that keeps memory "
                               "from growing with the log); choose a time_window of at most 9.999 s (10000 samples at "
                               "1000 Hz)");
  options.max_samples = 0;  // no bound
  EXPECT_EQ(Prepare(filtered, options).log.n_samples(), 30001);
  options.max_samples = -1;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_EQ(why, "max_samples: expected >= 0 (0: no bound), got -1");
}

}  // namespace
}  // namespace idbench
