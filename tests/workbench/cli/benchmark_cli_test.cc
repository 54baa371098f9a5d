// `idbench benchmark` as a user runs it: options refused before any work
// (exit 2, the flag named), a run sharded four ways and merged with
// `benchmark merge` gives the single run's benchmark.json.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_fixture.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::CliFixture;
using testing::Result;
using testing::Slurp;

class BenchmarkCliTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    std::ofstream(dir_ / "pid.json") << R"({"kp": [400, 400, 200], "kd": [10, 10, 5], "feedforward": "model"})";
    // The built-in general motion's harmonics, for 1 s.
    std::ofstream(dir_ / "short.json") << R"({"family": "fourier", "f0": 0.5, "duration": 1, "rest_to_rest": false,
      "q0": [0, 0, 0], "a": [[0.6, 0.25], [0.55, -0.25], [0.5, 0.25]],
      "b": [[0.3, -0.15], [0.34, -0.12], [0.38, -0.09]]})";
  }
  std::string Args(const std::string& more) const {
    return "benchmark --robot " IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf --trajectory " +
           (dir_ / "short.json").string() + " --controller " + (dir_ / "pid.json").string() +
           " --friction none --estimators ols,wls " + more;
  }
  // benchmark.json with every wall time removed: what a run determines.
  static nlohmann::json WithoutTimes(const fs::path& path) {
    nlohmann::json j = nlohmann::json::parse(Slurp(path));
    for (auto& r : j["results"]) r.erase("seconds");
    for (auto& t : j["trial_values"]) {
      for (auto& e : t["estimates"]) e.erase("seconds");
    }
    return j;
  }
};

TEST_F(BenchmarkCliTest, BadOptionsExitTwoNamingTheFlag) {
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--trials 0 --out " + (dir_ / "a").string(), "--trials: must be in [1, 100000], got 0"},
      {"--preset loud --out " + (dir_ / "a").string(), "--preset: expected none, low or high, got 'loud'"},
      {"--estimators ols,foo --out " + (dir_ / "a").string(), "--estimators: expected ols, wls, pc, tls, irls, iv or didim, got 'foo'"},
      {"--shard 1 --out " + (dir_ / "a").string(), "--shard: expected K/N"},
      {"--shard 4/4 --out " + (dir_ / "a").string(), "--shard: expected K/N with 0 <= K < N"},
  };
  for (const Case& c : cases) {
    const Result r = Run(Args(c.args));
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "a")) << c.args;
  }
  const Result r = Run("benchmark --robot puma560 --trials 2 --out " + (dir_ / "a").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--controller: "), std::string::npos) << r.err;
}

TEST_F(BenchmarkCliTest, FourShardsMergedGiveTheSingleRun) {
  const std::string run = "--trials 2 --preset low,high ";
  Result r = Run(Args(run + "--threads 2 --out " + (dir_ / "single").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("preset  estimator"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("benchmark: 4/4 trials"), std::string::npos) << r.err;
  EXPECT_GT(fs::file_size(dir_ / "single" / "parameter_errors.png"), 1000u);
  std::string dirs;
  for (int k = 0; k < 4; ++k) {
    const fs::path out = dir_ / ("shard" + std::to_string(k));
    r = Run(Args(run + "--shard " + std::to_string(k) + "/4 --out " + out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    dirs += " " + out.string();
  }
  r = Run("benchmark merge" + dirs + " --out " + (dir_ / "merged").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(WithoutTimes(dir_ / "merged" / "benchmark.json").dump(2),
            WithoutTimes(dir_ / "single" / "benchmark.json").dump(2));
  // The single run merged alone: its own bytes, wall times included.
  r = Run("benchmark merge " + (dir_ / "single").string() + " --out " + (dir_ / "again").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(dir_ / "again" / "benchmark.json"), Slurp(dir_ / "single" / "benchmark.json"));
  // A shard left out is named; nothing written.
  r = Run("benchmark merge " + (dir_ / "shard0").string() + " --out " + (dir_ / "partial").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("a shard is missing"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "partial"));
}

}  // namespace
}  // namespace idbench
