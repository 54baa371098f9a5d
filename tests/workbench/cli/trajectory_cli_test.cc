// --trajectory as a file (JSON or CSV), run as a user would.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "workbench/cli/cli_fixture.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::Result;
using testing::Slurp;

// One harmonic per joint of the PUMA, f0 = 0.25 Hz, 2 s:
//   q_j(t) = q0_j + a_j/ω sin(ωt) − b_j/ω cos(ωt),  ω = 2π·0.25.
constexpr double kF0 = 0.25, kDuration = 2.0;
const double kQ0[6] = {0.1, 0.5, -0.6, 0.2, -0.1, 0.3};
const double kA[6] = {0.4, -0.3, 0.35, 0.5, -0.45, 0.6};
const double kB[6] = {0.1, 0.2, -0.15, 0.05, 0.25, -0.2};

std::string FourierJson(double f0 = kF0) {
  std::ostringstream s;
  s.precision(17);
  s << R"({"family": "fourier", "f0": )" << f0 << R"(, "duration": )" << kDuration << R"(, "rest_to_rest": false, "q0": [)";
  for (int j = 0; j < 6; ++j) s << (j ? ", " : "") << kQ0[j];
  s << R"(], "a": [)";
  for (int j = 0; j < 6; ++j) s << (j ? ", " : "") << "[" << kA[j] << "]";
  s << R"(], "b": [)";
  for (int j = 0; j < 6; ++j) s << (j ? ", " : "") << "[" << kB[j] << "]";
  s << "]}\n";
  return s.str();
}

double AnalyticQ(int j, double t) {
  const double w = 2 * std::numbers::pi * kF0;
  return kQ0[j] + kA[j] / w * std::sin(w * t) - kB[j] / w * std::cos(w * t);
}

// Rows of a joint-log CSV (header skipped).
std::vector<std::vector<double>> Rows(const std::string& csv) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

class TrajectoryCliTest : public testing::CliFixture {};

// Bullet tracks the file's motion (computed torque from the exact start state)
// over the file's own duration; the logged positions converge to the analytic
// ones as O(dt) (the tracking lag of one explicit step: measured 4.9e-5 rad at
// dt = 1 ms, 4.9e-6 at 0.1 ms).
TEST_F(TrajectoryCliTest, SimulateFollowsAJsonTrajectoryFile) {
  std::ofstream(dir_ / "motion.json") << FourierJson();
  std::vector<std::vector<double>> rows;
  for (const double dt : {1e-4, 1e-3}) {
    const fs::path log = dir_ / "log.csv";
    const Result r = Run("simulate --robot puma560 --trajectory " + (dir_ / "motion.json").string() +
                         " --rate 100 --dt " + std::to_string(dt) + " --out " + log.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("for 2 s: 200 samples"), std::string::npos) << r.out;
    rows = Rows(Slurp(log));
    ASSERT_EQ(rows.size(), 200u);
    double worst = 0.0;
    for (const std::vector<double>& row : rows) {
      for (int j = 0; j < 6; ++j) worst = std::max(worst, std::abs(row[1 + j] - AnalyticQ(j, row[0])));
    }
    EXPECT_LT(worst, 0.1 * dt) << "dt = " << dt;
  }
  const fs::path log = dir_ / "log.csv";  // the dt = 1 ms run

  // The log is itself a trajectory (CSV, torques ignored): simulating along it
  // reproduces it.
  const fs::path again = dir_ / "again.csv";
  const Result r2 = Run("simulate --robot puma560 --trajectory " + log.string() + " --rate 100 --out " + again.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const std::vector<std::vector<double>> rows2 = Rows(Slurp(again));
  ASSERT_EQ(rows2.size(), 199u);  // 1.99 s: the last sample of the log ends the motion
  double diff = 0.0;
  for (size_t k = 0; k < rows2.size(); ++k) {
    for (int j = 0; j < 6; ++j) diff = std::max(diff, std::abs(rows2[k][1 + j] - rows[k][1 + j]));
  }
  EXPECT_LT(diff, 1e-4);  // one more tracking lag
}

// A bad file: exit 2 (the input is wrong), one message naming the file and the key, nothing written.
TEST_F(TrajectoryCliTest, BadTrajectoryFileNamesTheProblem) {
  const fs::path bad = dir_ / "bad.json";
  std::ofstream(bad) << FourierJson(0.0);
  const fs::path out = dir_ / "log.csv";
  struct Case {
    std::string command, expected;
  };
  const std::vector<Case> cases = {
      {"simulate --robot puma560 --trajectory " + bad.string() + " --out " + out.string(),
       bad.string() + ": key 'f0': must be > 0, got 0"},
      {"simulate --robot paper6r --trajectory " + (dir_ / "none.csv").string() + " --out " + out.string(),
       (dir_ / "none.csv").string() + ": cannot read the file"},
      {"simulate --robot puma560 --trajectory zigzag --out " + out.string(),
       "trajectory 'zigzag': not a built-in motion (paper, general, general-reversed) nor a file ending in .json or .csv"},
      {"montecarlo --robot puma560 --trials 2 --held-out " + bad.string(), bad.string() + ": key 'f0'"},
  };
  for (const Case& c : cases) {
    const Result r = Run(c.command);
    EXPECT_EQ(r.exit_code, 2) << c.command;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.command << "\n" << r.err;
    EXPECT_EQ(r.err.find("error:"), r.err.rfind("error:")) << "one message: " << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

// montecarlo: the held-out motion from a file.
TEST_F(TrajectoryCliTest, MonteCarloTakesAHeldOutFile) {
  std::ofstream(dir_ / "held.json") << FourierJson();
  const Result r = Run("montecarlo --robot puma560 --trials 3 --held-out " + (dir_ / "held.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("held-out torque relative error"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace idbench
