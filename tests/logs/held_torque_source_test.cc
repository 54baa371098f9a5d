// JointLogFormat::torque_held (held_torque_source.h): each torque read as the
// mean of its hold and the previous one's, across chunk boundaries and after
// Rewind; the truth is the file's torques averaged by hand.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <cmath>
#include <fstream>
#include <string>

#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"
#include "idbench/logs/joint_log_pipeline.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

TEST(HeldTorqueSourceTest, EachTorqueIsTheMeanOfItsHoldAndThePreviousOne) {
  const fs::path dir = fs::temp_directory_path() / ("idbench_held_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "log.csv";
  const int n = 50;
  auto tau = [](int k, int j) { return std::sin(0.3 * k + j) + 0.01 * k * k; };
  {
    std::ofstream out(path);
    out.precision(17);
    out << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
    for (int k = 0; k < n; ++k) {
      out << 0.01 * k;
      for (int j = 0; j < 6; ++j) out << "," << 0.001 * k;
      for (int j = 0; j < 6; ++j) out << "," << tau(k, j);
      out << "\n";
    }
  }
  const RobotModel model = MakePaper6r();
  JointLogFormat format;
  format.torque_held = true;
  for (Eigen::Index request : {1, 7, 100}) {
    const auto source = OpenJointLog(path.string(), model, format, TorqueColumns::kRequired);
    for (int pass = 0; pass < 2; ++pass) {
      JointLogChunk chunk;
      int k = 0;
      while (source->Next(request, &chunk)) {
        for (Eigen::Index r = 0; r < chunk.samples.t.size(); ++r, ++k) {
          for (int j = 0; j < 6; ++j) {
            const double expected = k == 0 ? tau(0, j) : 0.5 * (tau(k - 1, j) + tau(k, j));
            EXPECT_NEAR(chunk.samples.tau(r, j), expected, 1e-12) << "request " << request << ", sample " << k;
          }
        }
      }
      EXPECT_EQ(k, n);
      source->Rewind();
    }
    ASSERT_FALSE(source->layout().notes.empty());
    EXPECT_NE(source->layout().notes.back().find("zero-order hold"), std::string::npos);
  }
  // A log without torques has nothing to hold: said, naming the file.
  std::ofstream(dir / "q.csv") << "t,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n0.01,0,0,0,0,0,0\n";
  const std::string what = testing::ExpectInvalid(
      [&] { OpenJointLog((dir / "q.csv").string(), model, format, TorqueColumns::kOptional); });
  EXPECT_NE(what.find("q.csv: torque_held: the log has no torque (or current) columns"), std::string::npos) << what;
  fs::remove_all(dir);
}

// A log held in memory (PrepareRecordedJointLog: the benchmark's simulated
// logs, Python's arrays) reads its torques as held too when the format says
// so; before, its format was ignored and the torques read as recorded.
TEST(HeldTorqueSourceTest, ARecordedLogInMemoryIsReadAsHeldWhenTheFormatSaysSo) {
  const RobotModel model = MakePaper6r();
  const int n = 20;
  RecordedJointLog recorded;
  JointLog& log = recorded.log;
  log.t = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01 * (n - 1));
  log.q = Eigen::MatrixXd::Zero(n, 6);
  log.qd = Eigen::MatrixXd::Zero(n, 6);
  log.qdd = Eigen::MatrixXd::Zero(n, 6);
  log.tau.resize(n, 6);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < 6; ++j) log.tau(k, j) = std::sin(0.3 * k + j) + 0.01 * k * k;
  }
  for (int k = 0; k < n; ++k) recorded.lines.push_back(k);
  const Eigen::MatrixXd tau = log.tau;
  LogPreparationOptions options;
  options.format.torque_held = true;
  const PreparedLog prepared = PrepareRecordedJointLog(recorded, "arrays", options);
  ASSERT_EQ(prepared.log.tau.rows(), n);
  for (int k = 0; k < n; ++k) {
    const Eigen::RowVectorXd expected = k == 0 ? Eigen::RowVectorXd(tau.row(0)) : 0.5 * (tau.row(k - 1) + tau.row(k));
    EXPECT_LT((prepared.log.tau.row(k) - expected).cwiseAbs().maxCoeff(), 1e-12) << "sample " << k;
  }
  options.format.torque_held = false;
  EXPECT_EQ(PrepareRecordedJointLog(recorded, "arrays", options).log.tau, tau);
}

}  // namespace
}  // namespace idbench
