// `idbench compare --log`: recorded logs on the command line, with identify's
// log-reading flags; bad logs exit 2 naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "workbench/cli/cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using idbench::testing::CliFixture;
using idbench::testing::Result;

class CompareCliTest : public CliFixture {
 protected:
  Result Compare(const std::string& args) {
    return Run("compare --robot puma560 --trials 2 --out " + (dir_ / "c").string() + " " + args);
  }
};

// A log `simulate` wrote (200 Hz, t, q, qd, qdd, τ) and one without qd, qdd
// (filtered as identify does, --filter-cutoff applies) beside a built-in
// motion: all three ranked by cond and simulated, the logs over their span
// cut to whole samples·dt (0.25 s).
TEST_F(CompareCliTest, RecordedLogsAreRankedBesideTheMotions) {
  const fs::path log = dir_ / "log.csv", bare = dir_ / "bare.csv";
  ASSERT_EQ(Run("simulate --robot puma560 --trajectory general --rate 200 --out " + log.string()).exit_code, 0);
  ASSERT_EQ(Run("simulate --robot puma560 --trajectory general --rate 200 --no-derivatives --out " + bare.string())
                .exit_code, 0);
  const Result r = Compare("general --log " + log.string() + " --log " + bare.string() + " --filter-cutoff 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(idbench::testing::Slurp(dir_ / "c" / "compare.json"));
  ASSERT_EQ(c["motions"].size(), 3u);
  std::vector<std::pair<double, int>> by_cond;
  for (size_t m = 0; m < 3; ++m) {
    const nlohmann::json& motion = c["motions"][m];
    EXPECT_EQ(motion["recorded"].get<bool>(), m > 0);
    EXPECT_TRUE(motion["simulated"].get<bool>());
    EXPECT_GT(motion["mean_relative_error"].get<double>(), 0.0);
    by_cond.emplace_back(motion["designed"]["cond"].get<double>(), motion["rank"].get<int>());
  }
  EXPECT_EQ(c["motions"][1]["trajectory"].get<std::string>(), log.string());
  std::sort(by_cond.begin(), by_cond.end());
  for (int i = 0; i < 3; ++i) EXPECT_EQ(by_cond[static_cast<size_t>(i)].second, i + 1);
  // 9.995 s recorded: 9.75 s; without qd, qdd the filter's end transients
  // (5/cutoff = 0.625 s each end) dropped first: 8.745 s, so 8.5 s.
  EXPECT_NEAR(c["motions"][1]["duration"].get<double>(), 9.75, 1e-9);
  EXPECT_NEAR(c["motions"][2]["duration"].get<double>(), 8.5, 1e-9);
}

// compare reads a log as identify does and says so as identify does: the
// same notes before its table (a dropped line: "resampled ...") and the same
// warnings (a radian log read with --angle-unit deg: "is the log in
// radians?"; before, compare printed neither, and on the KUKA log cond 3.7e8
// without a word). Here the degrees leave the PUMA's motion too small to
// excite every parameter: the warning comes with that error.
TEST_F(CompareCliTest, SaysHowItReadTheLogsAsIdentifyDoes) {
  const fs::path whole = dir_ / "whole.csv", log = dir_ / "log.csv";
  ASSERT_EQ(Run("simulate --robot puma560 --trajectory general --rate 200 --no-derivatives --out " + whole.string())
                .exit_code, 0);  // q only: filtered, so resampled onto a uniform grid
  std::istringstream in(idbench::testing::Slurp(whole));
  std::ofstream out(log);
  int n = 0;
  for (std::string line; std::getline(in, line); ++n) {
    if (n != 500) out << line << "\n";  // one sample dropped: a 10 ms step among 5 ms ones
  }
  out.close();
  ASSERT_EQ(Run("identify --robot puma560 --data " + log.string() + " --out " + (dir_ / "id").string()).exit_code, 0);
  const nlohmann::json notes = nlohmann::json::parse(idbench::testing::Slurp(dir_ / "id" / "identified.json"))["log_preparation"];
  ASSERT_GE(notes.size(), 1u);
  EXPECT_NE(notes[0].get<std::string>().find("resampled"), std::string::npos) << notes.dump();
  const Result r = Compare("general --log " + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& note : notes) EXPECT_NE(r.out.find(note.get<std::string>() + "\n"), std::string::npos) << r.out;
  EXPECT_LT(r.out.find(notes[0].get<std::string>()), r.out.find("compare: torque model"));  // before the table, as identify
  // In degrees: identify's warnings, word for word.
  const Result id = Run("identify --robot puma560 --data " + log.string() + " --angle-unit deg --out " +
                        (dir_ / "deg").string());
  const Result deg = Compare("general --log " + log.string() + " --angle-unit deg");
  EXPECT_NE(deg.err.find("is the log in radians?"), std::string::npos) << deg.err;
  std::istringstream warnings(id.err);
  int n_warnings = 0;
  for (std::string line; std::getline(warnings, line);) {
    const std::string prefix = "idbench: warning: ";
    if (line.rfind(prefix, 0) != 0) continue;
    EXPECT_NE(deg.err.find(line.substr(prefix.size())), std::string::npos) << line << "\n" << deg.err;
    ++n_warnings;
  }
  EXPECT_GE(n_warnings, 1) << id.err;
}

TEST_F(CompareCliTest, BadLogsExitTwoNamingTheFile) {
  const fs::path missing = dir_ / "missing.csv";
  Result r = Compare("general --log " + missing.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;

  const fs::path garbled = dir_ / "garbled.csv";
  std::ofstream(garbled) << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n0,1,2,3,4,5,6,1,2,3,4,5,6\n0.1,1,2,x,4\n";
  r = Compare("--log " + garbled.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(garbled.string()), std::string::npos) << r.err;

  r = Compare("");  // no motion at all
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("at least one motion"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "c" / "compare.json"));
}

}  // namespace
