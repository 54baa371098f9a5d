// MakeRunReportContent (run_report_content.cc) as a library call: a run's
// report content holds the run's numbers, formatted exactly (checked against
// the RunReport's fields printed here): the experiment, one table row a
// parameter and one a body, and the four plots.
#include <gtest/gtest.h>

#include <string>

#include "idbench/engine/paper6r.h"
#include "idbench/workbench/reports/report_command.h"
#include "workbench/printf_test_util.h"

namespace idbench {
namespace {

using testing::Printf;

TEST(RunReportContentTest, HoldsTheRunsNumbersExactlyFormatted) {
  const RobotModel model = MakePaper6r();
  RunOptions options;
  options.command_line = "idbench run --report --out x";
  const RunReport report = RunExperiment(model, options);
  const PerBodyIdentificationResult& r = report.identification;
  const ReportContent content = MakeRunReportContent(model, options, report, "png bytes");

  EXPECT_EQ(content.title, "idbench run: paper6r, paper motion, per-body quaternion method");
  EXPECT_EQ(content.command, "idbench run --report --out x");
  EXPECT_EQ(content.pose_figure_png, "png bytes");
  ASSERT_EQ(content.experiment.size(), 5u);
  EXPECT_EQ(content.experiment[0], (std::pair<std::string, std::string>{"robot", "paper6r"}));
  EXPECT_EQ(content.experiment[1].second, "paper: hinges 1 and 2 accelerate at 30 deg/s², others locked");
  EXPECT_EQ(content.experiment[2].second, "2 s, 0.001 s (Bullet, joint feedback)");
  EXPECT_EQ(content.experiment[3].second, "5 (0.3, 0.6, 0.9, 1.2, 1.5 s)");
  EXPECT_EQ(content.experiment[4].second,
            Printf("%.3e", r.max_rel_error) + " (" + r.max_rel_error_at + "); the paper's: 3.1e-04");
  EXPECT_FALSE(r.max_rel_error_at.empty());

  // One row a parameter (6 bodies × 7), as the identification has it.
  ASSERT_EQ(content.tables.size(), 2u);
  const ReportTable& parameters = content.tables[0];
  ASSERT_EQ(parameters.header.size(), 7u);
  ASSERT_EQ(parameters.rows.size(), 42u);
  size_t row = 0;
  int n_identifiable = 0;
  for (const BodyResult& body : r.bodies) {
    for (const ParameterResult& p : body.parameters) {
      const std::vector<std::string>& cells = parameters.rows[row++];
      ASSERT_EQ(cells.size(), 7u);
      EXPECT_EQ(cells[0], body.name);
      EXPECT_EQ(cells[1], p.name);
      EXPECT_EQ(cells[2], Printf("%.6f", p.true_value)) << p.name;
      EXPECT_EQ(cells[3], p.identifiable ? Printf("%.12g", p.identified) : "-") << p.name;
      // An unidentifiable parameter has no error (NaN): a dash, not "nan".
      EXPECT_EQ(cells[4], p.identifiable ? Printf("%.3e", p.abs_error) : "-") << p.name;
      EXPECT_EQ(cells[5], p.identifiable ? Printf("%.2e", p.rel_error) : "-") << p.name;
      EXPECT_EQ(cells[6], p.identifiable ? "ok" : "NOT IDENTIFIABLE: " + p.reason) << p.name;
      n_identifiable += p.identifiable;
    }
  }
  // B1 turns about its own axis: 4 of its 7 parameters can never be identified.
  EXPECT_LE(n_identifiable, 38);
  EXPECT_EQ(parameters.rows[0][0], "B1");
  const ReportTable& blocks = content.tables[1];
  ASSERT_EQ(blocks.rows.size(), 6u);
  for (size_t b = 0; b < 6; ++b) {
    const BodyResult& body = r.bodies[b];
    EXPECT_EQ(blocks.rows[b][1], std::to_string(body.newton.rank) + "/" + std::to_string(body.newton.n_unknowns));
    EXPECT_EQ(blocks.rows[b][3], std::to_string(body.euler.rank) + "/" + std::to_string(body.euler.n_unknowns));
    EXPECT_EQ(blocks.rows[b][4], Printf("%.3g", body.euler.cond));
  }
  ASSERT_EQ(content.plots.size(), 4u);
  EXPECT_EQ(content.plots[0].stem, "joints");
  EXPECT_EQ(content.plots[1].stem, "parameters");
  EXPECT_EQ(content.plots[2].stem, "spectrum");
  EXPECT_EQ(content.plots[3].stem, "motions");
  EXPECT_NE(content.plots[3].caption.find("The paper motion against the general motion"), std::string::npos);
}

}  // namespace
}  // namespace idbench
