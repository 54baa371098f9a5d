#include "idbench/logs/recorded_joint_log_source.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench {
namespace {

// A 6-joint log of n samples with q, qd and tau (no qdd), lines from 2.
RecordedJointLog MakeLog(int n) {
  RecordedJointLog log;
  log.log.t = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01 * (n - 1));
  log.log.q = Eigen::MatrixXd::Random(n, 6) * 0.5;
  log.log.qd = Eigen::MatrixXd::Random(n, 6);
  log.log.tau = Eigen::MatrixXd::Random(n, 6) * 10.0;
  for (int k = 0; k < n; ++k) log.lines.push_back(k + 2);
  log.notes = {"a note"};
  log.warnings = {"a warning"};
  return log;
}

// Handing a log out in chunks of any size and gathering them back gives the
// log itself, bit for bit; a second pass after Rewind gives it again.
TEST(RecordedJointLogSourceTest, ChunksGatherBackToTheLog) {
  const RecordedJointLog truth = MakeLog(1003);
  for (Eigen::Index chunk : {1, 7, 1000, 1003, 5000}) {
    RecordedJointLogSource source(truth, "memory");
    EXPECT_EQ(source.layout().n_dof, 6);
    EXPECT_TRUE(source.layout().has_qd);
    EXPECT_FALSE(source.layout().has_qdd);
    EXPECT_TRUE(source.layout().has_tau);
    for (int pass = 0; pass < 2; ++pass) {
      const RecordedJointLog back = ReadWholeLog(source, chunk);
      ASSERT_EQ(back.log.t.size(), 1003) << "chunk " << chunk;
      EXPECT_EQ(back.log.t, truth.log.t);
      EXPECT_EQ(back.log.q, truth.log.q);
      EXPECT_EQ(back.log.qd, truth.log.qd);
      EXPECT_EQ(back.log.qdd.size(), 0);
      EXPECT_EQ(back.log.tau, truth.log.tau);
      EXPECT_EQ(back.lines, truth.lines);
      EXPECT_EQ(back.notes, truth.notes);
      EXPECT_EQ(back.warnings, truth.warnings);
      source.Rewind();
    }
  }
}

// Next hands out at most max_samples, in order, then false with an empty chunk.
TEST(RecordedJointLogSourceTest, NextStopsAtTheEnd) {
  RecordedJointLogSource source(MakeLog(10), "memory");
  JointLogChunk chunk;
  ASSERT_TRUE(source.Next(4, &chunk));
  EXPECT_EQ(chunk.samples.t.size(), 4);
  EXPECT_EQ(chunk.records.front(), 2);
  ASSERT_TRUE(source.Next(4, &chunk));
  EXPECT_EQ(chunk.records.front(), 6);
  ASSERT_TRUE(source.Next(4, &chunk));
  EXPECT_EQ(chunk.samples.t.size(), 2);
  EXPECT_FALSE(source.Next(4, &chunk));
  EXPECT_EQ(chunk.samples.t.size(), 0);
  EXPECT_THROW(source.Next(0, &chunk), std::invalid_argument);
}

// OpenJointLog on a CSV file gives what the whole-file reader gives.
TEST(RecordedJointLogSourceTest, OpenJointLogReadsACsvFileAsTheReaderDoes) {
  const RobotModel puma = MakePuma560();
  const std::string path = ::testing::TempDir() + "/open_joint_log.csv";
  {
    std::ofstream file(path);
    file << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
    for (int k = 0; k < 50; ++k) {
      file << 0.01 * k;
      for (int j = 0; j < 12; ++j) file << "," << 0.001 * (k + j);
      file << "\n";
    }
  }
  const RecordedJointLog direct = ReadRecordedJointLog(path, puma, {}, TorqueColumns::kRequired);
  auto source = OpenJointLog(path, puma, {}, TorqueColumns::kRequired);
  EXPECT_EQ(source->layout().source, path);
  const RecordedJointLog streamed = ReadWholeLog(*source, 16);
  EXPECT_EQ(streamed.log.t, direct.log.t);
  EXPECT_EQ(streamed.log.q, direct.log.q);
  EXPECT_EQ(streamed.log.tau, direct.log.tau);
  EXPECT_EQ(streamed.lines, direct.lines);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace idbench
