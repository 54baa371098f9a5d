#include "idbench/workbench/reports/report_command.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <regex>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

// Every word a reader sees in the report's content, one string.
std::string Words(const ReportContent& content) {
  std::string text = content.title + "\n" + content.pose_caption + "\n";
  for (const auto& [key, value] : content.experiment) text += key + ": " + value + "\n";
  for (const ReportTable& table : content.tables) {
    text += table.caption + "\n";
    for (const std::string& h : table.header) text += h + "\n";
  }
  for (const ReportPlot& plot : content.plots) {
    text += plot.caption + "\n";
    for (const PlotAxes& axes : plot.figure.axes) {
      text += axes.title + "\n" + axes.x_label + "\n" + axes.y_label + "\n";
      for (const PlotSeries& s : axes.series) text += s.label + "\n";
    }
  }
  return text;
}

bool HasWord(const std::string& text, const std::string& word) {
  return std::regex_search(text, std::regex("\\b" + word + "\\b", std::regex::icase));
}

// One noise-free puma560 log of 4 s at 100 Hz with qd, qdd, identified by
// OLS; its report as recorded and as simulated.
class IdentifyReportContentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("LP_NUM_THREADS", "1", 1);  // the pose figure renders with llvmpipe
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 4.0});
    RecordedJointLog recorded;
    recorded.log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(401, 0.0, 4.0));
    recorded.lines.resize(401);
    for (int s = 0; s < 401; ++s) recorded.lines[static_cast<size_t>(s)] = s + 2;
    options_.data = "log.csv";
    options_.estimator = TorqueEstimator::kOls;
    report_ = IdentifyPreparedLogs(model_, options_,
                                   PrepareRecordedJointLog(std::move(recorded), "log.csv", options_.preparation(true)),
                                   std::nullopt);
  }
  RobotModel model_ = MakePuma560();
  IdentifyOptions options_;
  IdentifyReport report_;
};

// A recorded log: nothing is called true or the truth; its torques are
// "measured"; the robot file is named as the reference; joints by name.
TEST_F(IdentifyReportContentTest, RecordedLogHasNoTruth) {
  const std::string text = Words(MakeIdentifyReportContent(model_, options_, report_, LogOrigin::kRecorded));
  EXPECT_FALSE(HasWord(text, "truth")) << text;
  EXPECT_FALSE(HasWord(text, "true")) << text;
  EXPECT_TRUE(HasWord(text, "recorded log")) << text;
  EXPECT_TRUE(HasWord(text, "measured")) << text;
  EXPECT_TRUE(HasWord(text, "robot file")) << text;
  EXPECT_TRUE(HasWord(text, "joint6, identification log")) << text;
  EXPECT_FALSE(HasWord(text, "simulated")) << text;
}

// A simulated log: the robot file that generated it is the truth, the
// torques are "simulated"; the same numbers either way.
TEST_F(IdentifyReportContentTest, SimulatedLogHasTheRobotFileAsTruth) {
  const ReportContent recorded = MakeIdentifyReportContent(model_, options_, report_, LogOrigin::kRecorded);
  const ReportContent simulated = MakeIdentifyReportContent(model_, options_, report_, LogOrigin::kSimulated);
  const std::string text = Words(simulated);
  EXPECT_TRUE(HasWord(text, "truth")) << text;
  EXPECT_TRUE(HasWord(text, "simulated log")) << text;
  EXPECT_FALSE(HasWord(text, "measured")) << text;
  ASSERT_EQ(simulated.tables.size(), recorded.tables.size());
  for (size_t t = 0; t < simulated.tables.size(); ++t) EXPECT_EQ(simulated.tables[t].rows, recorded.tables[t].rows);
}

}  // namespace
}  // namespace idbench
