#include "idbench/logs/streamed_log_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace idbench {
namespace {

// A 2-joint log at 1 kHz with noise: positions, a measured velocity, torques.
JointLog NoisyLog(Eigen::Index n) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n, 0.0, 1e-3 * static_cast<double>(n - 1));
  log.q.resize(n, 2);
  log.qd.resize(n, 2);
  log.tau.resize(n, 2);
  for (Eigen::Index s = 0; s < n; ++s) {
    const double t = log.t[s];
    log.q.row(s) << std::sin(1.3 * t) + 1e-4 * noise(rng), 0.5 * std::cos(0.7 * t) + 1e-4 * noise(rng);
    log.qd.row(s) << 1.3 * std::cos(1.3 * t) + 1e-2 * noise(rng), -0.35 * std::sin(0.7 * t) + 1e-2 * noise(rng);
    log.tau.row(s) << noise(rng), noise(rng);
  }
  return log;
}

// Streamed in blocks smaller than the margin, bigger than it, and one block
// for the whole log, with a last push of 1 sample: ProcessJointLog on the
// whole log to 1e-12 of each filtered signal's range, amplified by the
// differences (q from the positions, qd and qdd from them or from the measured
// velocity); τ passes unchanged.
TEST(StreamedLogFilterTest, EqualsProcessJointLogOnTheWholeLog) {
  const Eigen::Index n = 7001;
  for (bool with_qd : {false, true}) {
    JointLog log = NoisyLog(n);
    if (!with_qd) log.qd.resize(0, 0);
    const LogFilterOptions options{.order = 4, .cutoff_hz = 10.0, .trim_s = 0.0, .filter_tau = false};
    const JointLog whole = ProcessJointLog(log, options);
    for (Eigen::Index block : {700, 3000, 7001}) {
      SCOPED_TRACE(std::string(with_qd ? "qd recorded" : "q only") + ", block " + std::to_string(block));
      StreamedLogFilter filter(options, 1000.0, with_qd, false, 2, n, block);
      JointLog streamed = whole;
      Eigen::Index next = 0;
      auto sink = [&](const JointLog& prepared, Eigen::Index s0) {
        EXPECT_EQ(s0, next);
        const Eigen::Index m = prepared.n_samples();
        streamed.t.segment(s0, m) = prepared.t;
        streamed.q.middleRows(s0, m) = prepared.q;
        streamed.qd.middleRows(s0, m) = prepared.qd;
        streamed.qdd.middleRows(s0, m) = prepared.qdd;
        streamed.tau.middleRows(s0, m) = prepared.tau;
        next = s0 + m;
      };
      for (Eigen::Index s : {Eigen::Index{0}, Eigen::Index{4000}, n - 1}) {
        const Eigen::Index m = (s == 0 ? 4000 : s == 4000 ? n - 1 - 4000 : 1);
        JointLog chunk;
        chunk.t = log.t.segment(s, m);
        chunk.q = log.q.middleRows(s, m);
        if (with_qd) chunk.qd = log.qd.middleRows(s, m);
        chunk.tau = log.tau.middleRows(s, m);
        filter.Push(chunk, sink);
      }
      ASSERT_TRUE(filter.done());
      ASSERT_EQ(next, n);
      EXPECT_EQ(streamed.t, log.t);
      EXPECT_EQ(streamed.tau, log.tau);
      // Differences amplify the filtered signal's error e (rounding
      // included): to e/dt in a first and 4e/dt² in a second difference.
      const double dt = 1e-3, q_range = log.q.cwiseAbs().maxCoeff();
      const double qd_range = with_qd ? log.qd.cwiseAbs().maxCoeff() : q_range / dt;
      EXPECT_LT((streamed.q - whole.q).cwiseAbs().maxCoeff(), 1e-12 * q_range);
      EXPECT_LT((streamed.qd - whole.qd).cwiseAbs().maxCoeff(), 1e-12 * qd_range);
      EXPECT_LT((streamed.qdd - whole.qdd).cwiseAbs().maxCoeff(), 1e-12 * (with_qd ? qd_range / dt : 4.0 * q_range / (dt * dt)));
    }
  }
}

TEST(StreamedLogFilterTest, RejectsTooShortLogsAndWrongChunks) {
  const LogFilterOptions options;
  EXPECT_THROW(StreamedLogFilter(options, 1000.0, false, false, 2, 5), std::invalid_argument);
  EXPECT_THROW(StreamedLogFilter(options, 1000.0, true, true, 2, 500), std::invalid_argument);
  StreamedLogFilter filter(options, 1000.0, true, false, 2, 500);
  JointLog chunk = NoisyLog(10);
  chunk.qd.resize(0, 0);  // announced, not given
  EXPECT_THROW(filter.Push(chunk, [](const JointLog&, Eigen::Index) {}), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
