// identify --data A --data B: several logs of one robot, each prepared on its
// own, their equations stacked into one fit. Checked against a second
// algorithm: W and τ of both logs built row by row with the design's
// regressor (DesignRegressor::Rows, not the streamed fold) and solved with
// Eigen directly; σ's batch means never put two logs in one block.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/commands/identify_command.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

// Two puma560 logs with qd and qdd (used as read: no filter), of different
// motions (the general one, and one played backwards) and lengths, their
// torques with seeded noise so that the fit is not exact.
class IdentifySeveralLogsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_identify_several_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.05);
    const char* motions[] = {"general", "general-reversed"};
    const int samples[] = {1000, 1300};
    const double durations[] = {10.0, 13.0};
    for (int i = 0; i < 2; ++i) {
      const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion(motions[i], 6, {.duration = durations[i]});
      JointLog log =
          testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(samples[i], 0.0, durations[i]));
      for (Eigen::Index k = 0; k < log.tau.size(); ++k) log.tau.data()[k] += noise(rng);
      logs_.push_back(log);
      paths_.push_back((dir_ / ("log" + std::to_string(i) + ".csv")).string());
      std::ofstream(paths_.back()) << FormatJointLogCsv(log);
    }
    options_.data = paths_[0];
    options_.more_data = {paths_[1]};
    options_.friction = {"viscous", "coulomb"};
    options_.estimator = TorqueEstimator::kOls;
    options_.out_dir = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  // W (rows interleaved by joint) and τ of a log, from the design's regressor.
  void Rows(const JointLog& log, const DesignRegressor& regressor, Eigen::MatrixXd* W, Eigen::VectorXd* tau) const {
    const int n = model_.n_dof();
    DesignRegressor::Workspace ws(model_);
    W->resize(log.n_samples() * n, regressor.n_parameters());
    tau->resize(log.n_samples() * n);
    JointState x(n);
    for (Eigen::Index s = 0; s < log.n_samples(); ++s) {
      x.q = log.q.row(s).transpose();
      x.qd = log.qd.row(s).transpose();
      x.qdd = log.qdd.row(s).transpose();
      regressor.Rows(x, &ws, W->middleRows(s * n, n));
      tau->segment(s * n, n) = log.tau.row(s).transpose();
    }
  }

  RobotModel model_ = MakePuma560();
  IdentifyOptions options_;
  std::vector<JointLog> logs_;
  std::vector<std::string> paths_;
  fs::path dir_;
};

TEST_F(IdentifySeveralLogsTest, StackingEqualsSolvingTheConcatenatedEquations) {
  const IdentifyReport report = RunIdentify(model_, options_);
  ASSERT_EQ(report.status, IdentifyStatus::kDone);
  const DesignRegressor regressor = DesignRegressor::JointTorque(model_, options_.friction_model());
  ASSERT_EQ(regressor.base().names, report.identification.base.names);
  Eigen::MatrixXd W0, W1;
  Eigen::VectorXd tau0, tau1;
  Rows(logs_[0], regressor, &W0, &tau0);
  Rows(logs_[1], regressor, &W1, &tau1);
  Eigen::MatrixXd W(W0.rows() + W1.rows(), W0.cols());
  Eigen::VectorXd tau(tau0.size() + tau1.size());
  W << W0, W1;
  tau << tau0, tau1;
  const Eigen::VectorXd beta = W.colPivHouseholderQr().solve(tau);
  EXPECT_LT((report.identification.beta - beta).norm(), 1e-8 * beta.norm());

  // Per log: its samples and its own cond(W); the fit's cond is the union's.
  EXPECT_EQ(report.n_samples, 2300);
  EXPECT_EQ(report.n_samples_read, 2300);
  ASSERT_EQ(report.parts.size(), 2u);
  auto cond = [](const Eigen::MatrixXd& A) {
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
    return s(0) / s(s.size() - 1);
  };
  EXPECT_EQ(report.parts[0].path, paths_[0]);
  EXPECT_EQ(report.parts[1].n_samples, 1300);
  EXPECT_NEAR(report.parts[0].cond, cond(W0), 1e-8 * cond(W0));
  EXPECT_NEAR(report.parts[1].cond, cond(W1), 1e-8 * cond(W1));
  EXPECT_NEAR(report.identification.linear.cond, cond(W), 1e-8 * cond(W));

  // σ: batch means of blocks within each log: ⌈1000/L⌉ + ⌈1300/L⌉ blocks.
  const CovarianceSummary& c = report.identification.linear.covariance_method;
  ASSERT_EQ(c.method, CovarianceMethod::kBatchMeans);
  const Eigen::Index L = c.block_samples;
  EXPECT_EQ(c.n_blocks, (1000 + L - 1) / L + (1300 + L - 1) / L) << "block length " << L;
  EXPECT_EQ(c.n_samples, 2300);

  // The table names each log, then the one fit; identified.json lists both files.
  const std::string table = FormatIdentifyTables(model_, options_, report);
  EXPECT_NE(table.find("log 1 of 2, " + paths_[0] + ": 1000 samples, cond(W) = "), std::string::npos) << table;
  EXPECT_NE(table.find("log 2 of 2, " + paths_[1] + ": 1300 samples, cond(W) = "), std::string::npos) << table;
  EXPECT_NE(table.find("from the 2 logs stacked: 2300 samples used"), std::string::npos) << table;
  const nlohmann::json j = nlohmann::json::parse(FormatIdentifiedJson(model_, options_, report));
  EXPECT_EQ(j["data_files"], nlohmann::json(paths_));
}

// One log as today: no per-log lines, the same fit as with the log alone.
TEST_F(IdentifySeveralLogsTest, OneLogPrintsNoPerLogLines) {
  options_.more_data.clear();
  const IdentifyReport report = RunIdentify(model_, options_);
  EXPECT_TRUE(report.parts.empty());
  const std::string table = FormatIdentifyTables(model_, options_, report);
  EXPECT_EQ(table.find("log 1 of"), std::string::npos);
  EXPECT_NE(table.find("Joint-torque identification of puma560 from " + paths_[0] + ": 1000 samples,"),
            std::string::npos)
      << table;
}

}  // namespace
}  // namespace idbench
