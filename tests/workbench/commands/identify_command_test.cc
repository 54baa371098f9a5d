// RunIdentify's control (IdentifyControl): progress over a whole run is
// non-decreasing and reaches 1; a stop set from the progress callback ends
// the run with IdentifyStatus::kCancelled and nothing written; a run with a
// control identifies exactly as one without.
#include "idbench/workbench/commands/identify_command.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

// A puma560 log of 30 s at 1 kHz (t, q, qd, qdd, τ): ~4 streaming blocks per
// pass, held out on itself, so a run has 6 stages (2 reads, 2 folds, the
// solve, the second pass for σ).
class IdentifyCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_identify_command_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 30.0});
    const JointLog log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(30001, 0.0, 30.0));
    options_.data = options_.validate = (dir_ / "log.csv").string();
    std::ofstream(options_.data) << FormatJointLogCsv(log);
    options_.friction = {"viscous", "coulomb"};
    options_.estimator = TorqueEstimator::kOls;
    options_.out_dir = (dir_ / "out").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  RobotModel model_ = MakePuma560();
  IdentifyOptions options_;
  fs::path dir_;
};

TEST_F(IdentifyCommandTest, ProgressIsMonotoneAndReachesOne) {
  std::vector<IdentifyProgress> reports;
  IdentifyControl control;
  control.progress = [&](const IdentifyProgress& p) { reports.push_back(p); };
  const IdentifyReport report = RunIdentify(model_, options_, control);
  ASSERT_EQ(report.status, IdentifyStatus::kDone);
  ASSERT_FALSE(reports.empty());
  for (size_t k = 1; k < reports.size(); ++k) EXPECT_GE(reports[k].fraction, reports[k - 1].fraction) << k;
  EXPECT_GE(reports.front().fraction, 0.0);
  EXPECT_EQ(reports.back().fraction, 1.0);
  EXPECT_EQ(reports.back().stage, "done");
  // Reported within the passes too: every stage start (k/6) and blocks between.
  int inside = 0;
  for (const IdentifyProgress& p : reports) inside += p.fraction > 0.0 && p.fraction < 1.0 && p.fraction * 6 != std::round(p.fraction * 6);
  EXPECT_GE(inside, 8);
  // The same numbers as a run without a control.
  const IdentifyReport plain = RunIdentify(model_, options_);
  EXPECT_EQ(report.identification.beta, plain.identification.beta);
  EXPECT_EQ(report.validation->relative_error, plain.validation->relative_error);
}

TEST_F(IdentifyCommandTest, StopFromTheProgressCallbackCancels) {
  std::atomic<bool> stop{false};
  double stopped_at = -1.0, last = -1.0;
  IdentifyControl control;
  control.stop = &stop;
  control.progress = [&](const IdentifyProgress& p) {
    last = p.fraction;
    if (p.fraction >= 0.3 && !stop) {
      stop = true;
      stopped_at = p.fraction;
    }
  };
  const IdentifyReport report = RunIdentify(model_, options_, control);
  EXPECT_EQ(report.status, IdentifyStatus::kCancelled);
  EXPECT_GE(stopped_at, 0.3);
  EXPECT_EQ(last, stopped_at);  // nothing reported once stopped
  EXPECT_EQ(report.n_samples, 0);
  EXPECT_FALSE(report.prepared);
  EXPECT_FALSE(fs::exists(options_.out_dir));
  // Stopped before it starts: cancelled at once.
  const IdentifyReport before = RunIdentify(model_, options_, control);
  EXPECT_EQ(before.status, IdentifyStatus::kCancelled);
}

// What the fit used, counted (IdentifyReport::n_samples, n_samples_read,
// the summary line, identified.json) on a 6-joint log of 1001 samples at
// 100 Hz (t = 0..10 s), decimated by 3, against the arithmetic by hand:
//  - with qd and qdd recorded (no filter): samples 0, 3, …, 999 kept,
//    ⌈1001/3⌉ = 334; in the time window 2..8 s, 601 samples read, 201 used;
//  - with t, q, τ only (qd, qdd by filtering at 10 Hz): 5/10 Hz = 0.5 s =
//    50 samples dropped at each end, then one in 3: ⌈(1001 − 100)/3⌉ = 301.
// Before, a filtered log's summary said "1001 samples", the count read.
TEST(IdentifySampleCountTest, TheSummaryCountsWhatTheFitUsed) {
  const fs::path dir = fs::temp_directory_path() / ("idbench_identify_counts_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const RobotModel model = MakePuma560();
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  JointLog log = testing::SyntheticJointLog(model, *motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
  IdentifyOptions options;
  options.data = (dir / "full.csv").string();
  std::ofstream(options.data) << FormatJointLogCsv(log);
  options.friction = {"viscous", "coulomb"};
  options.estimator = TorqueEstimator::kOls;
  options.filter.decimation = 3;
  auto headline = [&](const IdentifyReport& report) {
    const std::string tables = FormatIdentifyTables(model, options, report);
    const size_t at = tables.find("Joint-torque identification of");
    return at == std::string::npos ? tables : tables.substr(at, tables.find('\n', at) - at);
  };
  auto json_counts = [&](const IdentifyReport& report) {
    const nlohmann::json j = nlohmann::json::parse(FormatIdentifiedJson(model, options, report));
    return std::make_pair(j["n_samples"].get<long>(), j["n_samples_read"].get<long>());
  };

  const IdentifyReport full = RunIdentify(model, options);
  EXPECT_EQ(full.n_samples_read, 1001);
  EXPECT_EQ(full.n_samples, 334);
  EXPECT_EQ(json_counts(full), std::make_pair(334L, 1001L));
  char cond[32];
  std::snprintf(cond, sizeof cond, "%.4g", full.identification.linear.cond);
  EXPECT_EQ(headline(full), "Joint-torque identification of puma560 from " + options.data +
                                ": 1001 samples read, 334 used (one in 3 kept), 48 base parameters, estimator ols, "
                                "cond(W) = " + cond);
  options.time_window = {2.0, 8.0};
  const IdentifyReport windowed = RunIdentify(model, options);
  EXPECT_EQ(windowed.n_samples_read, 601);
  EXPECT_EQ(windowed.n_samples, 201);
  EXPECT_NE(headline(windowed).find(": 601 samples read, 201 used (one in 3 kept), "), std::string::npos)
      << headline(windowed);
  options.time_window.clear();

  log.qd.resize(0, 0);
  log.qdd.resize(0, 0);
  options.data = (dir / "raw.csv").string();
  std::ofstream(options.data) << FormatJointLogCsv(log);
  const IdentifyReport filtered = RunIdentify(model, options);
  ASSERT_TRUE(filtered.filtered);
  EXPECT_EQ(filtered.n_samples_read, 1001);
  EXPECT_EQ(filtered.n_samples, (1001 - 2 * 50 + 2) / 3);
  EXPECT_EQ(filtered.n_samples, 301);
  EXPECT_EQ(json_counts(filtered), std::make_pair(301L, 1001L));
  EXPECT_NE(headline(filtered).find(": 1001 samples read, 301 used (qd, qdd from the filtered q; 50 filter-transient "
                                    "samples dropped at each end, then one in 3 kept), 48 base parameters"),
            std::string::npos) << headline(filtered);
  // Not decimated: only the filter's ends are dropped, 1001 − 100.
  options.filter.decimation = 1;
  const IdentifyReport undecimated = RunIdentify(model, options);
  EXPECT_EQ(undecimated.n_samples, 901);
  EXPECT_NE(headline(undecimated).find(": 1001 samples read, 901 used (qd, qdd from the filtered q; 50 "
                                       "filter-transient samples dropped at each end), "),
            std::string::npos) << headline(undecimated);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace idbench
