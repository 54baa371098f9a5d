// RunOptionsFromResultsJson (report_json.cc) as a library call: the run
// options read back from the results.json a run wrote are the options it ran
// with, so that running them again writes the same results.json byte for
// byte; a missing or mistyped key is named with the file.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "idbench/engine/paper6r.h"
#include "idbench/workbench/commands/run_command.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench {
namespace {

class ReportJsonTest : public ::testing::Test {
 protected:
  // results.json of a run with `options`.
  std::string ResultsJson(const RunOptions& options) {
    return FormatRunResultsJson(options, RunExperiment(model_, options));
  }
  // The message RunOptionsFromResultsJson throws for `text`, "" if none.
  static std::string Error(const std::string& text) {
    try {
      RunOptionsFromResultsJson(text, "run/results.json");
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  RobotModel model_ = MakePaper6r();
};

TEST_F(ReportJsonTest, PaperRunReadsBackAsItsOptions) {
  RunOptions options;
  options.accel_deg_s2 = 45.0;
  options.duration = 1.5;
  options.dt = 2e-3;
  options.sample_times = {0.25, 0.5, 1.0, 1.25};
  options.command_line = "idbench run --accel 45 --duration 1.5 --dt 0.002 --samples 0.25,0.5,1,1.25";
  const std::string text = ResultsJson(options);
  const nlohmann::json json = nlohmann::json::parse(text);
  const RunOptions read = RunOptionsFromResultsJson(text, "results.json");

  EXPECT_EQ(read.robot, "paper6r");
  EXPECT_EQ(read.robot, json["robot"].get<std::string>());
  EXPECT_EQ(read.motion, "paper");
  EXPECT_EQ(read.accel_deg_s2, 45.0);
  EXPECT_EQ(read.duration, 1.5);
  EXPECT_EQ(read.dt, 2e-3);
  EXPECT_EQ(read.command_line, options.command_line);
  EXPECT_FALSE(read.all_samples);
  // The sample times are the logged steps' times (k·dt), the asked ones to rounding.
  ASSERT_EQ(read.sample_times.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(read.sample_times[i], options.sample_times[i], 1e-12) << i;
    EXPECT_EQ(read.sample_times[i], json["sample_times"][i].get<double>()) << i;
  }
  EXPECT_EQ(json["n_steps"].get<size_t>(), 750u);  // t = 0, 0.002, …, 1.498 (docs/commands/run.md)
  // Run again from what was read: the same results.json.
  EXPECT_EQ(ResultsJson(read), text);
}

// The general motion has no acceleration to record (it keeps the default);
// every step sampled reads back as all_samples with no times.
TEST_F(ReportJsonTest, GeneralRunOfEveryStepReadsBackAsAllSamples) {
  RunOptions options;
  options.motion = "general";
  options.accel_deg_s2 = 12.0;  // not used by the general motion, not recorded
  options.duration = 0.5;
  options.all_samples = true;
  const std::string text = ResultsJson(options);
  const nlohmann::json json = nlohmann::json::parse(text);
  ASSERT_FALSE(json.contains("accel_deg_s2"));
  EXPECT_EQ(json["sample_times"].size(), json["n_steps"].get<size_t>());
  EXPECT_EQ(json["n_steps"].get<size_t>(), 500u);  // t = 0, 0.001, …, 0.499
  EXPECT_EQ(json["sample_times"].front().get<double>(), 0.0);
  EXPECT_NEAR(json["sample_times"].back().get<double>(), 0.499, 1e-12);

  const RunOptions read = RunOptionsFromResultsJson(text, "results.json");
  EXPECT_EQ(read.motion, "general");
  EXPECT_EQ(read.accel_deg_s2, RunOptions().accel_deg_s2);
  EXPECT_EQ(read.duration, 0.5);
  EXPECT_EQ(read.dt, 1e-3);
  EXPECT_TRUE(read.all_samples);
  EXPECT_TRUE(read.sample_times.empty());
  EXPECT_EQ(read.command_line, "");
  EXPECT_EQ(ResultsJson(read), text);
}

TEST_F(ReportJsonTest, MissingOrMistypedKeyIsNamedWithTheFile) {
  const nlohmann::json json = nlohmann::json::parse(ResultsJson(RunOptions()));
  EXPECT_EQ(Error(json.dump()), "");
  for (const char* key : {"robot", "motion", "accel_deg_s2", "duration", "dt", "sample_times", "command", "n_steps"}) {
    nlohmann::json missing = json;
    missing.erase(key);
    EXPECT_EQ(Error(missing.dump()), std::string("run/results.json: key '") + key + "': missing");
    nlohmann::json mistyped = json;
    mistyped[key] = nlohmann::json::object();
    EXPECT_EQ(Error(mistyped.dump()), std::string("run/results.json: key '") + key + "': wrong type");
  }
  // The general motion needs no acceleration.
  nlohmann::json general = json;
  general["motion"] = "general";
  general.erase("accel_deg_s2");
  EXPECT_EQ(Error(general.dump()), "");

  EXPECT_EQ(Error("{\"robot\": ").substr(0, 33), "run/results.json: not valid JSON:");
  EXPECT_EQ(Error("").substr(0, 33), "run/results.json: not valid JSON:");
  // Issue 35 items 3 and 9, as for every JSON input (json_input.h).
  EXPECT_EQ(Error("{\"robot\": \"puma560\", \"robot\": \"paper6r\"}"),
            "run/results.json: .robot: key repeated in one object (each key may be given once)");
  EXPECT_NE(Error("{\"robot\": " + std::string(100'000, '[') + std::string(100'000, ']') + "}")
                .find(": more than 64 nested arrays and objects"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench
