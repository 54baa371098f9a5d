// RunExperiment as a library call: the brief report of the paper's default
// experiment names what ran and the parameters identified, against the
// results.json the command writes for the same run and against the paper
// (B1 turns about its own axis with its centroid on it: its m along e1, e2 and
// its J22, J33 cannot be identified from any motion of paper6r).
#include "idbench/workbench/commands/run_command.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

TEST(RunCommandTest, BriefReportAgreesWithResultsJson) {
  const RobotModel model = MakePaper6r();
  RunOptions options;
  const RunReport report = RunExperiment(model, options);
  const std::string brief = report.BriefReport();
  const nlohmann::json json = nlohmann::json::parse(FormatRunResultsJson(options, report));

  // What ran: 2 s of 1 ms steps, the five sample times.
  EXPECT_EQ(brief.substr(0, brief.find('\n')),
            "idbench run: paper6r, paper motion, 2000 steps of 0.001 s, 5 samples, per-body quaternion method");
  // The parameters identified, counted in results.json.
  int n_parameters = 0, n_identified = 0;
  for (const auto& body : json["bodies"]) {
    for (const auto& p : body["parameters"]) {
      ++n_parameters;
      n_identified += p["identifiable"].get<bool>();
    }
  }
  EXPECT_EQ(n_parameters, 42);  // 6 bodies x 7
  EXPECT_NE(brief.find("\n" + std::to_string(n_identified) + " of 42 parameters identified; not identifiable: "),
            std::string::npos)
      << brief;
  for (const char* never : {"B1.m_e1", "B1.m_e2", "B1.J22", "B1.J33"}) {
    EXPECT_NE(brief.find(never), std::string::npos) << never << "\n" << brief;
  }
  // The largest error and where, as results.json has them (3 digits printed).
  const std::string last = brief.substr(brief.rfind('\n', brief.size() - 2) + 1);
  double largest = 0.0, paper = 0.0;
  char at[32] = {};
  ASSERT_EQ(std::sscanf(last.c_str(), "largest relative error over identifiable parameters: %le (%31[^)]); the paper's: %le",
                        &largest, at, &paper),
            3)
      << last;
  EXPECT_NEAR(largest, json["max_rel_error"].get<double>(), 1e-3 * json["max_rel_error"].get<double>());
  EXPECT_EQ(std::string(at), json["max_rel_error_at"].get<std::string>());
  EXPECT_EQ(paper, json["paper_max_rel_error"].get<double>());
  EXPECT_LT(largest, paper);
  // The table opens and closes with the same lines.
  const std::string tables = FormatRunTables(options, report);
  EXPECT_EQ(tables.substr(0, brief.find('\n') + 1), brief.substr(0, brief.find('\n') + 1));
  EXPECT_EQ(tables.substr(tables.size() - last.size()), last);
}

}  // namespace
}  // namespace idbench
