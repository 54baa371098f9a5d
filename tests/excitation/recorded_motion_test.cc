#include "idbench/excitation/recorded_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace idbench {
namespace {

// A 2-joint log of q = (sin t, t²) with its exact derivatives at 10 Hz.
JointLog SineLog(double t0, int n) {
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n, t0, t0 + 0.1 * (n - 1));
  log.q.resize(n, 2);
  log.qd.resize(n, 2);
  log.qdd.resize(n, 2);
  log.tau = Eigen::MatrixXd::Zero(n, 2);
  for (int s = 0; s < n; ++s) {
    const double t = log.t[s];
    log.q.row(s) << std::sin(t), t * t;
    log.qd.row(s) << std::cos(t), 2 * t;
    log.qdd.row(s) << -std::sin(t), 2.0;
  }
  return log;
}

// Exact at the samples, linear between them (each of q, qd, qdd on its own),
// time from the first sample, held at the ends.
TEST(RecordedMotionTest, InterpolatesEachSignalLinearlyBetweenSamples) {
  const JointLog log = SineLog(2.0, 11);
  const RecordedMotion motion(log, 1.0);
  EXPECT_EQ(motion.n_dof(), 2);
  EXPECT_DOUBLE_EQ(motion.duration(), 1.0);
  JointState x(2);
  motion.Evaluate(0.3, &x);
  EXPECT_LT((x.q - log.q.row(3).transpose()).norm(), 1e-12);
  EXPECT_LT((x.qdd - log.qdd.row(3).transpose()).norm(), 1e-12);
  motion.Evaluate(0.35, &x);
  EXPECT_LT((x.qd - 0.5 * (log.qd.row(3) + log.qd.row(4)).transpose()).norm(), 1e-12);
  motion.Evaluate(5.0, &x);  // beyond the last sample: the last sample
  EXPECT_LT((x.q - log.q.row(10).transpose()).norm(), 1e-12);
}

// A filtered log loses the filter's end transients (ParallelFilterTrimSamples
// at each end), one used as recorded loses nothing; too little left is an
// error naming the log.
TEST(RecordedMotionTest, FilteredLogsLoseTheirEndTransients) {
  PreparedLog prepared;
  prepared.log = SineLog(0.0, 101);  // 10 s at 10 Hz
  std::unique_ptr<RecordedMotion> motion = MakeRecordedMotion(prepared, "log.csv");
  EXPECT_NEAR(motion->duration(), 10.0, 1e-12);

  prepared.parallel_filter = ParallelFilter{LogFilterOptions{.order = 2, .cutoff_hz = 2.0, .trim_s = -1.0}, 10.0};
  const Eigen::Index trim = ParallelFilterTrimSamples(prepared.parallel_filter->filter, 10.0);
  ASSERT_EQ(trim, 25);  // 5/cutoff = 2.5 s
  motion = MakeRecordedMotion(prepared, "log.csv");
  EXPECT_NEAR(motion->duration(), 10.0 - 2 * 2.5, 1e-9);
  JointState x(2);
  motion->Evaluate(0.0, &x);
  EXPECT_LT((x.q - prepared.log.q.row(trim).transpose()).norm(), 1e-12);

  prepared.log = SineLog(0.0, 51);  // 5 s: nothing left between the transients
  try {
    MakeRecordedMotion(prepared, "short.csv");
    FAIL() << "a log shorter than its transients was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("short.csv: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace idbench
