// RunGains as a library call on logs written as a user records them (motor
// currents i = τ/K of known gains K): the brief report gives the gains the
// logs were written with, the estimate's residuals and its verdict; the logs
// swapped are refused (not observed), the report saying why.
#include "idbench/workbench/commands/gains_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"
#include "workbench/cli/joint_log_writer.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class GainsCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_gains_command_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const Eigen::Matrix3d inertia = Eigen::Vector3d(4e-3, 5e-3, 3e-3).asDiagonal();
    unloaded_ = WriteCurrents("unloaded.csv", model_);
    loaded_ = WriteCurrents("loaded.csv", testing::WithPayload(model_, 2.5, {0.02, -0.03, 0.08}, inertia));
    options_.payload_mass = 2.5;
    options_.format.columns = {"t", "q1..q6", "qd1..qd6", "qdd1..qdd6", "i1..i6"};
    options_.out_dir = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  // t, q, qd, qdd, i = τ/K, no header; 10 s at 100 Hz.
  std::string WriteCurrents(const std::string& name, const RobotModel& model) {
    const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
    const JointLog log = testing::SyntheticJointLog(model, *motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
    std::ofstream(dir_ / name) << testing::JointLogCsvText(log, {"t", "q", "qd", "qdd", "i"}, false, gains_);
    return (dir_ / name).string();
  }

  const Eigen::VectorXd gains_ = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, -6.2, 4.1).finished();  // [N m/A]
  RobotModel model_ = MakePuma560();
  GainsOptions options_;
  std::string unloaded_, loaded_;
  fs::path dir_;
};

TEST_F(GainsCommandTest, BriefReportGivesTheGainsAndTheVerdict) {
  options_.data = unloaded_;
  options_.loaded = loaded_;
  std::string why;
  ASSERT_TRUE(options_.IsValid(&why)) << why;
  const GainsReport report = RunGains(model_, options_);
  ASSERT_TRUE(report.good()) << report.estimate.message;
  EXPECT_EQ(report.status(), DriveGainStatus::kEstimated);
  const std::string brief = report.BriefReport();
  std::istringstream lines(brief);
  std::string headline, gains, residual, verdict, more;
  std::getline(lines, headline);
  std::getline(lines, gains);
  std::getline(lines, residual);
  std::getline(lines, verdict);
  EXPECT_FALSE(std::getline(lines, more)) << brief;
  EXPECT_EQ(headline, "Drive gains of puma560 from " + unloaded_ + " (unloaded, 1001 samples) and " + loaded_ +
                          " (payload 2.5 kg, 1001 samples): " + std::to_string(report.estimate.unknown_names.size()) +
                          " unknowns, rank " + std::to_string(report.estimate.rank));
  // The gains the currents were written with, to the 6 digits printed.
  double K[6];
  double worst_percent = 0.0;
  int worst_joint = 0;
  ASSERT_EQ(std::sscanf(gains.c_str(), "K [N m/A]: %lg, %lg, %lg, %lg, %lg, %lg (largest %%sigma %lg, joint %d)", &K[0],
                        &K[1], &K[2], &K[3], &K[4], &K[5], &worst_percent, &worst_joint),
            8)
      << gains;
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(K[j], gains_[j], 5e-6 * std::abs(gains_[j])) << "K" << j + 1;
  EXPECT_GE(worst_joint, 1);
  EXPECT_LE(worst_joint, 6);
  EXPECT_LT(worst_percent, 1e-4);  // noise-free
  // The residuals, as the table prints them.
  EXPECT_NE(FormatGainsTable(model_, options_, report).find(residual + "\n"), std::string::npos) << residual;
  double unloaded_error = 1.0, loaded_error = 1.0;
  ASSERT_EQ(std::sscanf(residual.c_str(), "Relative torque residual: unloaded %lg, loaded %lg", &unloaded_error,
                        &loaded_error),
            2)
      << residual;
  EXPECT_LT(unloaded_error, 1e-9);
  EXPECT_LT(loaded_error, 1e-9);
  EXPECT_EQ(verdict, "estimated");
}

// The unloaded log given as the loaded one and vice versa: the payload would
// have to be negative and every K·i opposes the robot file's torques.
TEST_F(GainsCommandTest, SwappedLogsAreNotObserved) {
  options_.data = loaded_;
  options_.loaded = unloaded_;
  const GainsReport report = RunGains(model_, options_);
  EXPECT_EQ(report.status(), DriveGainStatus::kNotObserved) << report.estimate.message;
  EXPECT_FALSE(report.good());
  const std::string brief = report.BriefReport();
  const std::string verdict = "\nnot observed: " + report.estimate.message + "\n";
  ASSERT_GE(brief.size(), verdict.size());
  EXPECT_EQ(brief.substr(brief.size() - verdict.size()), verdict) << brief;
  EXPECT_NE(report.estimate.message.find("swapped"), std::string::npos) << report.estimate.message;
}

// The logs are held whole, so each is bounded: one of more prepared samples
// than LogPreparationOptions::kMaxHeldSamples is refused after the counting
// pass (before any is held), naming the log, its samples, the bound and the
// fix in the option's field (loaded_time_window for the loaded log).
TEST_F(GainsCommandTest, LogsLongerThanTheBoundAreRefused) {
  const Eigen::Index n = LogPreparationOptions::kMaxHeldSamples + 1;  // at 1 kHz, standing still
  {
    std::ofstream long_log(dir_ / "long.csv");
    char line[32];
    for (Eigen::Index s = 0; s < n; ++s) {
      std::snprintf(line, sizeof(line), "%.3f", static_cast<double>(s) * 1e-3);
      long_log << line << ",0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,1,1,1,1,1,1\n";
    }
  }
  options_.data = unloaded_;
  options_.loaded = (dir_ / "long.csv").string();
  std::string message;
  try {
    RunGains(model_, options_);
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  EXPECT_EQ(message, options_.loaded + ": 200001 samples to hold whole, more than 200000 (the bound that keeps memory "
                     "from growing with the log); choose a loaded_time_window of at most 199.999 s (200000 samples at "
                     "1000 Hz), or a filter.decimation of at least 2");
}

}  // namespace
}  // namespace idbench
