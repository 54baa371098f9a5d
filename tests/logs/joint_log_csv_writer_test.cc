#include "idbench/logs/joint_log_csv_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/logs/joint_log_csv_reader.h"

namespace idbench {
namespace {

// A log of the PUMA 560 with values of all magnitudes (q within ±0.5 rad,
// inside every joint's limits); qd, qdd and tau only when asked for.
JointLog RandomLog(int n_samples, bool derivatives, bool torques) {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random = [&](double scale) {
    Eigen::MatrixXd m(n_samples, 6);
    for (int s = 0; s < n_samples; ++s)
      for (int j = 0; j < 6; ++j) m(s, j) = scale * unit(rng) * std::pow(10.0, 3.0 * unit(rng));
    return m;
  };
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n_samples, 0.0, 0.1 * (n_samples - 1));
  log.q = random(0.5e-3);
  if (derivatives) {
    log.qd = random(1.0);
    log.qdd = random(1.0);
  }
  if (torques) log.tau = random(1.0);
  return log;
}

// The writer's header names the columns the log has, in the reader's order,
// and every number reads back exactly (shortest round-trip decimals).
TEST(JointLogCsvWriterTest, WritesTheColumnsTheLogHasAndReadsBackExactly) {
  const RobotModel puma = MakePuma560();
  const JointLog full = RandomLog(40, true, true);
  const std::string text = FormatJointLogCsv(full);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,qdd1,qdd2,qdd3,qdd4,qdd5,qdd6,tau1,tau2,tau3,tau4,tau5,tau6");
  const JointLog read = ParseJointLogCsv(text, puma, "w.csv");
  EXPECT_EQ(read.t, full.t);
  EXPECT_EQ(read.q, full.q);
  EXPECT_EQ(read.qd, full.qd);
  EXPECT_EQ(read.qdd, full.qdd);
  EXPECT_EQ(read.tau, full.tau);

  const JointLog positions = RandomLog(5, false, false);
  const std::string q_only = FormatJointLogCsv(positions);
  EXPECT_EQ(q_only.substr(0, q_only.find('\n')), "t,q1,q2,q3,q4,q5,q6");
  const JointLog read_q = ParseJointLogCsv(q_only, puma, "q.csv", TorqueColumns::kOptional);
  EXPECT_EQ(read_q.q, positions.q);
  EXPECT_EQ(read_q.qd.size(), 0);
  EXPECT_EQ(read_q.tau.size(), 0);
}

// A closed loop's log adds its reference, qr1..qrn, after the torques; the
// readers skip those columns and read the rest exactly (before, "qr1" was an
// unknown column and the log was refused).
TEST(JointLogCsvWriterTest, ReferenceColumnsAreWrittenLastAndSkippedByTheReader) {
  const RobotModel puma = MakePuma560();
  const JointLog log = RandomLog(10, false, true);
  const Eigen::MatrixXd q_ref = RandomLog(10, false, false).q * 2.0;
  const std::string text = FormatJointLogCsv(log, &q_ref);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6,qr1,qr2,qr3,qr4,qr5,qr6");
  const JointLog read = ParseJointLogCsv(text, puma, "closed.csv");
  EXPECT_EQ(read.q, log.q);
  EXPECT_EQ(read.tau, log.tau);
  const Eigen::MatrixXd wrong(3, 6);
  EXPECT_THROW(FormatJointLogCsv(log, &wrong), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
