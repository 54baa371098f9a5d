// The log plot's envelope (log_envelope.h) against the samples themselves: a
// sine whose period is the bucket interval, which keeping every k-th sample
// turns into a flat line (and a period 1 % longer into a slow sine), keeps
// its whole swing in every bucket; each bucket's min, max and mean are those
// of its samples; memory stays within 2 max_buckets buckets.
#include "idbench/gui/log_envelope.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "idbench/engine/paper6r.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench::gui {
namespace {

constexpr double kPi = 3.14159265358979323846;

// 40 s at 1 kHz, six joints: joint 1 a sine of period 16 ms (the bucket
// interval 2000 buckets come to: 16 samples), joint 2 of period 16.16 ms,
// the others slow sines; tau zero.
JointLog AliasingLog() {
  const Eigen::Index n = 40001;
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n, 0.0, 40.0);
  log.q.resize(n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = log.t[i];
    log.q(i, 0) = 0.5 * std::sin(2 * kPi * t / 0.016 + 0.3);
    log.q(i, 1) = 0.4 * std::sin(2 * kPi * t / 0.01616) - 0.2;
    for (int j = 2; j < 6; ++j) log.q(i, j) = 0.1 * j * std::sin(2 * kPi * 0.05 * j * t);
  }
  log.tau = Eigen::MatrixXd::Zero(n, 6);
  return log;
}

// The first n samples of a log (t and q).
JointLog Head(const JointLog& log, Eigen::Index n) {
  JointLog head;
  head.t = log.t.head(n);
  head.q = log.q.topRows(n);
  return head;
}

// Folded as the log source hands it out: chunks of 4096 samples; the bucket
// count checked after each.
LogEnvelope Fold(const JointLog& log, Eigen::Index max_buckets) {
  LogEnvelope envelope(max_buckets);
  for (Eigen::Index i = 0; i < log.t.size(); i += 4096) {
    const Eigen::Index m = std::min<Eigen::Index>(4096, log.t.size() - i);
    envelope.Add(log.t.segment(i, m), log.q.middleRows(i, m));
    EXPECT_LE(envelope.n_buckets(), 2 * max_buckets);
  }
  return envelope;
}

// Every bucket's min and max are those of the samples in [t_begin, t_end]
// (so they bracket them, and are reached), its mean theirs; the buckets tile
// the log in time order.
void ExpectEnvelopeOf(const LogEnvelope& envelope, const JointLog& log) {
  ASSERT_GT(envelope.n_buckets(), 0);
  EXPECT_EQ(envelope.n_samples(), log.t.size());
  EXPECT_EQ(envelope.t_begin(0), log.t[0]);
  EXPECT_EQ(envelope.t_end(envelope.n_buckets() - 1), log.t[log.t.size() - 1]);
  const Eigen::MatrixXd mean = envelope.Mean();
  Eigen::Index i = 0;
  for (Eigen::Index k = 0; k < envelope.n_buckets(); ++k) {
    if (k > 0) {
      ASSERT_GT(envelope.t_begin(k), envelope.t_end(k - 1));
    }
    Eigen::RowVectorXd lo = log.q.row(i), hi = log.q.row(i), sum = Eigen::RowVectorXd::Zero(log.q.cols());
    long long count = 0;
    for (; i < log.t.size() && log.t[i] <= envelope.t_end(k); ++i, ++count) {
      ASSERT_GE(log.t[i], envelope.t_begin(k));
      ASSERT_TRUE((envelope.min().row(k).array() <= log.q.row(i).array()).all()) << "bucket " << k << ", sample " << i;
      ASSERT_TRUE((envelope.max().row(k).array() >= log.q.row(i).array()).all()) << "bucket " << k << ", sample " << i;
      lo = lo.cwiseMin(log.q.row(i)), hi = hi.cwiseMax(log.q.row(i)), sum += log.q.row(i);
    }
    ASSERT_EQ(envelope.count(k), count) << "bucket " << k;
    ASSERT_EQ(envelope.min().row(k), lo) << "bucket " << k;
    ASSERT_EQ(envelope.max().row(k), hi) << "bucket " << k;
    ASSERT_LE((mean.row(k) - sum / static_cast<double>(count)).cwiseAbs().maxCoeff(), 1e-12) << "bucket " << k;
  }
  EXPECT_EQ(i, log.t.size());
}

TEST(LogEnvelopeTest, ASineAtTheBucketIntervalKeepsItsSwingInEveryBucket) {
  const JointLog log = AliasingLog();
  const LogEnvelope envelope = Fold(log, 2000);
  // 40001 samples: buckets of 16 (stride 16 for the old decimation), 2501 of them.
  EXPECT_EQ(envelope.samples_per_bucket(), 16);
  EXPECT_EQ(envelope.n_buckets(), 2501);
  ExpectEnvelopeOf(envelope, log);
  // The plot's range is the log's, per joint and over all.
  EXPECT_NEAR(envelope.min().minCoeff(), log.q.minCoeff(), 1e-12);
  EXPECT_NEAR(envelope.max().maxCoeff(), log.q.maxCoeff(), 1e-12);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(envelope.min().col(j).minCoeff(), log.q.col(j).minCoeff(), 1e-12) << "joint " << j + 1;
    EXPECT_NEAR(envelope.max().col(j).maxCoeff(), log.q.col(j).maxCoeff(), 1e-12) << "joint " << j + 1;
  }
  // Every 16th sample (what the plot kept before) shows joint 1 flat and
  // joint 2 as a sine of period 1.6 s; the envelope holds each swing whole
  // in every bucket of 16 samples (one period: all 16 phases of joint 1).
  const Eigen::Index stride = envelope.samples_per_bucket();
  double kept_lo = 1e9, kept_hi = -1e9;
  for (Eigen::Index i = 0; i < log.t.size(); i += stride)
    kept_lo = std::min(kept_lo, log.q(i, 0)), kept_hi = std::max(kept_hi, log.q(i, 0));
  EXPECT_LT(kept_hi - kept_lo, 1e-9);
  const double swing = log.q.col(0).maxCoeff() - log.q.col(0).minCoeff();
  EXPECT_GT(swing, 0.99);
  for (Eigen::Index k = 0; k + 1 < envelope.n_buckets(); ++k) {
    ASSERT_NEAR(envelope.max()(k, 0) - envelope.min()(k, 0), swing, 1e-12) << "bucket " << k;
    ASSERT_GT(envelope.max()(k, 1) - envelope.min()(k, 1), 0.95 * 0.8) << "bucket " << k;
  }
  std::printf("joint 1: every 16th sample spans %.3g rad, each bucket %.6g rad (the log %.6g rad)\n",
              kept_hi - kept_lo, envelope.max()(0, 0) - envelope.min()(0, 0), swing);
}

TEST(LogEnvelopeTest, MemoryStaysBoundedAndShortLogsKeepEverySample) {
  // Fewer samples than 2 max_buckets: one bucket per sample, the samples themselves.
  JointLog log = AliasingLog();
  const JointLog short_log = Head(log, 300);
  const LogEnvelope every = Fold(short_log, 200);
  EXPECT_EQ(every.n_buckets(), 300);
  EXPECT_EQ(every.min(), short_log.q);
  EXPECT_EQ(every.max(), short_log.q);
  // Any length: between max_buckets and 2 max_buckets buckets, each a power
  // of two samples (the last the rest), in one chunk or many.
  for (Eigen::Index n : {401, 402, 1000, 4096, 40001}) {
    const JointLog part = Head(log, n);
    const LogEnvelope envelope = Fold(part, 100);
    EXPECT_GE(envelope.n_buckets(), 100);
    EXPECT_LE(envelope.n_buckets(), 200);
    ExpectEnvelopeOf(envelope, part);
    LogEnvelope whole(100);
    whole.Add(part.t, part.q);
    EXPECT_EQ(whole.n_buckets(), envelope.n_buckets());
    EXPECT_EQ(whole.min(), envelope.min());
    EXPECT_EQ(whole.max(), envelope.max());
  }
  EXPECT_THROW(LogEnvelope(0), std::invalid_argument);
  LogEnvelope envelope(10);
  envelope.Add(log.t.head(3), log.q.topRows(3));
  EXPECT_THROW(envelope.Add(log.t.segment(3, 2), log.q.block(3, 0, 2, 5)), std::invalid_argument);
  EXPECT_THROW(envelope.Add(log.t.segment(3, 2), log.q.block(3, 0, 3, 6)), std::invalid_argument);
}

// The log plot's read: the CSV file streamed through OpenJointLog gives the
// envelope of the samples in memory, number for number; a stop ends it.
TEST(LogEnvelopeTest, FoldsAJointLogFileAsItsSamples) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("idbench_log_envelope_" + std::to_string(::getpid()) + ".csv");
  const JointLog log = AliasingLog();
  std::ofstream(path) << FormatJointLogCsv(log);
  const RobotModel model = MakePaper6r();
  std::atomic<bool> stop{false};
  LogEnvelope read(2000);
  ASSERT_TRUE(FoldJointPositions(*OpenJointLog(path.string(), model, {}, TorqueColumns::kOptional), stop, &read));
  const LogEnvelope direct = Fold(log, 2000);
  EXPECT_EQ(read.n_buckets(), direct.n_buckets());
  EXPECT_EQ(read.min(), direct.min());
  EXPECT_EQ(read.max(), direct.max());
  ExpectEnvelopeOf(read, log);
  stop = true;
  LogEnvelope stopped(2000);
  EXPECT_FALSE(FoldJointPositions(*OpenJointLog(path.string(), model, {}, TorqueColumns::kOptional), stop, &stopped));
  EXPECT_EQ(stopped.n_samples(), 0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace idbench::gui
