// MakeDesignReportContent as a library call on a real, small design (PUMA 560,
// 3 harmonics, 2 starts, 40 evaluations): the report's experiment, its
// identifiability, margin and start tables carry the DesignResult's numbers
// (printed here with the formats the page promises), the pose figure is the
// designed motion's eight default instants, and the plots are the motion's
// signals and W's spectra.
#include "idbench/workbench/reports/design_report.h"

#include <gtest/gtest.h>

#include <string>

#include "excitation/design_test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/render/png_codec.h"
#include "workbench/commands/quick_design_options.h"
#include "workbench/printf_test_util.h"

namespace idbench {
namespace {

using testing::Printf;

TEST(DesignReportTest, ContentCarriesTheDesignsNumbers) {
  const RobotModel model = MakePuma560();
  DesignCommandOptions options = testing::QuickDesignOptions("puma560");
  options.design.seed = 7;
  options.design.max_evaluations = 40;
  options.command_line = "idbench design --robot puma560 --report";
  const DesignCommandReport report = RunDesign(model, options, testing::DesignLimits(model, 1.5, 4.0), {});
  ASSERT_EQ(report.status(), DesignStatus::kFeasible);
  const DesignResult& r = report.result;
  const ReportContent content = MakeDesignReportContent(model, options, report);

  EXPECT_EQ(content.title.substr(0, 25), "idbench design: puma560, ");
  EXPECT_EQ(content.command, options.command_line);
  // The experiment: criterion start → design, the series, samples, search.
  ASSERT_EQ(content.experiment.size(), 7u);
  const auto value = [&](const std::string& key) {
    for (const auto& [k, v] : content.experiment) {
      if (k == key) return v;
    }
    ADD_FAILURE() << "no experiment row '" << key << "'";
    return std::string();
  };
  const std::string criterion = value("criterion");
  EXPECT_NE(criterion.find(": " + Printf("%.6g", r.initial_value) + " → " + Printf("%.6g", r.value)), std::string::npos)
      << criterion;
  EXPECT_EQ(value("trajectory"), "Fourier series, 3 harmonics of 0.2 Hz over 5 s");  // 1/f0, periodic
  EXPECT_EQ(value("samples"), "60");
  const std::string search = value("search");
  EXPECT_NE(search.find(", 2 starts from seed 7, " + std::to_string(r.evaluations) + " evaluations in " +
                        Printf("%.3g", r.wall_seconds) + " s"),
            std::string::npos)
      << search;
  EXPECT_LE(r.evaluations, 2 * 40);
  EXPECT_EQ(value("clearance"), "not checked");
  EXPECT_EQ(value("check at 1000 Hz"), "feasible");

  // Identifiability before and after, the margins, the starts.
  ASSERT_EQ(content.tables.size(), 3u);
  const ReportTable& identifiability = content.tables[0];
  ASSERT_EQ(identifiability.rows.size(), 2u);
  EXPECT_EQ(identifiability.rows[0], (std::vector<std::string>{"start", Printf("%.5g", r.initial.cond),
                                                                Printf("%.5g", r.initial.cond_normalised),
                                                                Printf("%.5g", r.initial.log_det),
                                                                Printf("%.5g", r.initial.sigma_min),
                                                                Printf("%.5g", r.initial.sigma_max)}));
  EXPECT_EQ(identifiability.rows[1][0], "designed");
  EXPECT_EQ(identifiability.rows[1][1], Printf("%.5g", r.final.cond));
  EXPECT_LT(r.final.cond, r.initial.cond);
  const ReportTable& margins = content.tables[1];
  ASSERT_EQ(margins.rows.size(), r.check.margins.size());
  ASSERT_FALSE(margins.rows.empty());
  for (size_t k = 0; k < margins.rows.size(); ++k) {
    const ConstraintMargin& m = r.check.margins[k];
    EXPECT_EQ(margins.rows[k][0], std::to_string(m.joint + 1)) << k;  // no clearance checked
    EXPECT_EQ(margins.rows[k][1], m.quantity) << k;
    EXPECT_EQ(margins.rows[k][2], Printf("%.5g", m.value)) << k;
    EXPECT_EQ(margins.rows[k][4], Printf("%.3g", m.margin)) << k;
    EXPECT_GE(m.margin, 0.0) << k;  // feasible
  }
  const ReportTable& starts = content.tables[2];
  ASSERT_EQ(starts.rows.size(), 2u);
  int evaluations = 0;
  for (size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(starts.rows[s][0], std::to_string(s + 1));
    EXPECT_EQ(starts.rows[s][1], std::to_string(7 + s));
    EXPECT_EQ(starts.rows[s][3], Printf("%.6g", r.starts[s].best_value));
    EXPECT_EQ(starts.rows[s][4], std::to_string(r.starts[s].evaluations));
    evaluations += r.starts[s].evaluations;
  }
  EXPECT_EQ(evaluations, r.evaluations);

  // The figure: eight default instants of the 5 s motion, 480×360 panels in two rows.
  const Image figure = DecodePng(content.pose_figure_png);
  EXPECT_EQ(figure.width, 4 * 480);
  EXPECT_EQ(figure.height, 2 * 360);
  ASSERT_EQ(content.plots.size(), 2u);
  EXPECT_EQ(content.plots[0].stem, "joints");
  EXPECT_EQ(content.plots[1].stem, "spectrum");
}

}  // namespace
}  // namespace idbench
