// idbench gains, run as a user would: an unloaded and a loaded log of the
// same robot, header-less with motor currents.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"
#include "workbench/cli/cli_fixture.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::Result;
using testing::Slurp;

class GainsCliTest : public testing::CliFixture {
 protected:
  const Eigen::VectorXd gains_ = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, -6.2, 4.1).finished();  // [N m/A]

  // t, q, qd, qdd, i = τ/K, a column of 7s (ignored), no header; 10 s at 100 Hz.
  fs::path WriteCurrents(const std::string& name, const RobotModel& model) {
    const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
    const JointLog log = testing::SyntheticJointLog(model, *motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
    std::string text;
    char number[32];
    for (int k = 0; k < log.n_samples(); ++k) {
      std::snprintf(number, sizeof(number), "%.17g", log.t[k]);
      text += number;
      for (const Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd, &log.tau}) {
        for (int j = 0; j < 6; ++j) {
          std::snprintf(number, sizeof(number), ",%.17g", x == &log.tau ? (*x)(k, j) / gains_[j] : (*x)(k, j));
          text += number;
        }
      }
      text += ",7\n";
    }
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
};

constexpr const char* kColumns = " --columns t,q1..q6,qd1..qd6,qdd1..qdd6,i1..i6";

// The check: an unloaded/loaded pair with a 2.5 kg payload, noise-free:
// gains.json holds the gains to 1e-6, with σ; they identify the robot through
// `identify --drive-gains`.
TEST_F(GainsCliTest, UnloadedAndLoadedLogsGiveTheGains) {
  const RobotModel puma = MakePuma560();
  const Eigen::Matrix3d inertia = Eigen::Vector3d(4e-3, 5e-3, 3e-3).asDiagonal();
  const fs::path unloaded = WriteCurrents("unloaded.csv", puma);
  const fs::path loaded = WriteCurrents("loaded.csv", testing::WithPayload(puma, 2.5, {0.02, -0.03, 0.08}, inertia));
  const Result r = Run("gains --robot puma560 --data " + unloaded.string() + " --loaded " + loaded.string() +
                       " --payload-mass 2.5" + kColumns + " --out " + (dir_ / "g").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("K [N m/A]"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(Slurp(dir_ / "g" / "gains.json"));
  ASSERT_EQ(j["drive_gains"].size(), 6u);
  ASSERT_EQ(j["sigma"].size(), 6u);
  double worst = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double gain = j["drive_gains"][k];
    worst = std::max(worst, std::abs(gain - gains_[k]) / std::abs(gains_[k]));
    EXPECT_NEAR(gain, gains_[k], 1e-6 * std::abs(gains_[k])) << "K" << k + 1;
    EXPECT_LT(j["sigma"][k].get<double>(), 1e-6 * std::abs(gains_[k]));
  }
  std::printf("gains from the CLI: worst relative error %.3g\n", worst);
  // Identify from the currents with the gains just found.
  std::string gains_arg;
  for (const auto& g : j["drive_gains"]) gains_arg += (gains_arg.empty() ? "" : ",") + std::to_string(g.get<double>());
  const Result id = Run("identify --robot puma560 --data " + unloaded.string() + kColumns + " --drive-gains " +
                        gains_arg + " --out " + (dir_ / "id").string());
  ASSERT_EQ(id.exit_code, 0) << id.err;
  EXPECT_LT(nlohmann::json::parse(Slurp(dir_ / "id" / "identified.json"))["fit"]["relative_error"].get<double>(), 1e-5);
}

// Two unloaded logs (the "payload" never fixed): the mass is not in the
// torques, the gains' scale is not determined: a message, exit 1, nothing
// written. Bad options: exit 2.
TEST_F(GainsCliTest, PairThatDoesNotDetermineTheGainsFails) {
  const fs::path unloaded = WriteCurrents("unloaded.csv", MakePuma560());
  const fs::path again = WriteCurrents("unloaded_again.csv", MakePuma560());  // a second recording, as it were
  const Result r = Run("gains --robot puma560 --data " + unloaded.string() + " --loaded " + again.string() +
                       " --payload-mass 2.5" + kColumns + " --out " + (dir_ / "g").string());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "g"));
  const std::string base = "gains --robot puma560 --data " + unloaded.string() + " --loaded " + again.string();
  EXPECT_EQ(Run(base + " --payload-mass 0" + kColumns).exit_code, 2);
  EXPECT_EQ(Run(base + " --payload-mass 1 --columns t,q1..q6,tau1..tau6,bogus").exit_code, 2);
  const Result no_currents = Run(base + " --payload-mass 1 --columns t,q1..q6,qd1..qd6,qdd1..qdd6,tau1..tau6");
  EXPECT_EQ(no_currents.exit_code, 2);  // the log lacks what gains needs: a wrong input
  EXPECT_NE(no_currents.err.find("missing column 'i1'"), std::string::npos) << no_currents.err;
}

// One file given as both logs, however spelled (./x.csv and x.csv, a link):
// refused before anything is read, exit 2, naming both; two windows of one
// file are two logs.
TEST_F(GainsCliTest, TheSameFileTwiceIsRefused) {
  const fs::path unloaded = WriteCurrents("unloaded.csv", MakePuma560());
  fs::create_symlink(unloaded, dir_ / "link.csv");
  const std::string common = " --payload-mass 2.5" + std::string(kColumns) + " --out " + (dir_ / "g").string();
  for (const std::string& other : {(dir_ / "." / "unloaded.csv").string(), (dir_ / "link.csv").string()}) {
    const Result r = Run("gains --robot puma560 --data " + unloaded.string() + " --loaded " + other + common);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_NE(r.err.find("--loaded: expected the log with the payload, got '" + other + "', the unloaded log '" +
                         unloaded.string() + "' again (the same file)"), std::string::npos) << r.err;
  }
  const Result windows = Run("gains --robot puma560 --data " + unloaded.string() + " --loaded " +
                             (dir_ / "link.csv").string() + " --time-window 0,5 --loaded-time-window 5,10" + common);
  EXPECT_NE(windows.exit_code, 2) << windows.err;  // runs (two parts of one recording)
  EXPECT_FALSE(fs::exists(dir_ / "g"));
}

// A log longer than the bound on what gains holds (200 000 samples): exit 2
// before it is held, one message naming the log, its samples, the bound and
// the --time-window that fits (q only: the filter's decimation would not
// shrink what is held), nothing written.
TEST_F(GainsCliTest, LogLongerThanTheBoundIsRefused) {
  const fs::path unloaded = WriteCurrents("unloaded.csv", MakePuma560());
  const fs::path long_log = dir_ / "long.csv";
  {
    std::ofstream out(long_log);
    char line[32];
    for (int s = 0; s <= 200000; ++s) {
      std::snprintf(line, sizeof(line), "%.3f", s * 1e-3);
      out << line << ",0,0,0,0,0,0,1,1,1,1,1,1\n";
    }
  }
  const Result r = Run("gains --robot puma560 --data " + long_log.string() + " --loaded " + unloaded.string() +
                       " --payload-mass 2.5 --columns t,q1..q6,i1..i6 --out " + (dir_ / "g").string());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const size_t error = r.err.find("idbench: error: ");  // after the robot file's warning
  ASSERT_NE(error, std::string::npos) << r.err;
  EXPECT_EQ(r.err.substr(error), "idbench: error: " + long_log.string() + ": 200001 samples to hold whole, more than 200000 (the "
                   "bound that keeps memory from growing with the log); choose a --time-window of at most 199.999 s "
                   "(200000 samples at 1000 Hz)\n");
  EXPECT_FALSE(fs::exists(dir_ / "g"));
}

}  // namespace
}  // namespace idbench
