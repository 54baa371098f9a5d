// The workbench's plots as drawn: read back from the PDF with pdftotext
// (poppler-utils), every axes of a torque comparison carries tick labels and
// its units.
#include "idbench/workbench/reports/plots.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace idbench {
namespace {

namespace fs = std::filesystem;

// The words of a PDF with their boxes, as `pdftotext -bbox` prints them.
struct Word {
  double x0, y0, x1, y1;
  std::string text;
};

std::vector<Word> PdfWords(const std::string& pdf, const fs::path& dir) {
  const fs::path file = dir / "plot.pdf", text = dir / "plot.html";
  std::ofstream(file, std::ios::binary) << pdf;
  EXPECT_EQ(std::system(("pdftotext -bbox " + file.string() + " " + text.string()).c_str()), 0);
  std::stringstream html;
  html << std::ifstream(text).rdbuf();
  std::vector<Word> words;
  const std::regex word(R"re(xMin="([-\d.]+)" yMin="([-\d.]+)" xMax="([-\d.]+)" yMax="([-\d.]+)">([^<]*)</word>)re");
  const std::string s = html.str();
  for (auto it = std::sregex_iterator(s.begin(), s.end(), word); it != std::sregex_iterator(); ++it) {
    words.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4]), (*it)[5]});
  }
  return words;
}

class PlotsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("command -v pdftotext >/dev/null 2>&1") != 0) GTEST_SKIP() << "pdftotext (poppler-utils) not installed";
    dir_ = fs::temp_directory_path() / ("idbench_plots_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Seven joints of small torque ranges (one of 1.1 N m, where a nice step of
// 0.5 would leave two labels): each axes has its title with the joint's
// name, t [s] and τ [N m], and at least three numeric labels on each axis.
TEST_F(PlotsTest, EveryTorqueAxesHasTicksAndUnits) {
  constexpr int kJoints = 7, kSamples = 500;
  TorqueSeries series;
  series.t.resize(kSamples);
  series.measured.resize(kSamples, kJoints);
  series.predicted.resize(kSamples, kJoints);
  for (int i = 0; i < kSamples; ++i) {
    series.t[i] = 0.05 * i;
    for (int j = 0; j < kJoints; ++j) {
      series.measured(i, j) = -0.2 + 0.55 * std::sin(0.01 * i * (j + 1));
      series.predicted(i, j) = 0.95 * series.measured(i, j);
    }
  }
  std::vector<std::string> names;
  for (int j = 0; j < kJoints; ++j) names.push_back("lwr_" + std::to_string(j) + "_joint");
  const PlotFigure figure = TorqueComparisonPlot(series, {"recorded log", "measured", names});
  ASSERT_EQ(figure.axes.size(), static_cast<size_t>(kJoints));
  const std::vector<Word> words = PdfWords(RenderPlot(figure, PlotFormat::kPdf), dir_);
  // Words per axes cell: the figure is 2 columns of cells, rows of equal height.
  const double cell_w = figure.width / figure.columns, cell_h = figure.height / ((kJoints + 1) / 2);
  const std::regex number(R"(^[-−]?\d+(\.\d+)?$)");
  for (int j = 0; j < kJoints; ++j) {
    const double x0 = (j % 2) * cell_w, y0 = (j / 2) * cell_h;
    int y_numbers = 0, x_numbers = 0, seconds = 0, newton_metres = 0, titles = 0;
    for (const Word& w : words) {
      const double cx = 0.5 * (w.x0 + w.x1), cy = 0.5 * (w.y0 + w.y1);
      if (cx < x0 || cx > x0 + cell_w || cy < y0 || cy > y0 + cell_h) continue;
      // y tick labels stand left of the plot area (64 pt of margin), x ones under it.
      if (std::regex_match(w.text, number)) ++(cx < x0 + 64.0 ? y_numbers : x_numbers);
      seconds += w.text == "[s]";
      newton_metres += w.text == "[N";
      titles += w.text == names[static_cast<size_t>(j)] + ",";
    }
    EXPECT_GE(y_numbers, 3) << names[static_cast<size_t>(j)];
    EXPECT_GE(x_numbers, 3) << names[static_cast<size_t>(j)];
    EXPECT_EQ(seconds, 1) << names[static_cast<size_t>(j)];
    EXPECT_EQ(newton_metres, 1) << names[static_cast<size_t>(j)];
    EXPECT_EQ(titles, 1) << names[static_cast<size_t>(j)];
  }
  // Nothing drawn outside the figure.
  for (const Word& w : words) {
    EXPECT_GE(w.x0, -0.5) << w.text;
    EXPECT_LE(w.x1, figure.width + 0.5) << w.text;
  }
}

// The box plot's numbers against NumPy's percentiles (type 7: linear between
// order statistics): np.percentile([1, 2, 3, 4], [25, 50, 75]) = 1.75, 2.5,
// 3.25; of [4, 1, 100, 3, 2, nan]: 2, 3, 4, with 100 beyond 4 + 1.5·2.
TEST(BenchmarkPlotTest, BoxesAreTukeysOnNumpysPercentiles) {
  const BoxSummary even = SummarizeBox({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(even.q1, 1.75);
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.q3, 3.25);
  EXPECT_DOUBLE_EQ(even.whisker_low, 1.0);
  EXPECT_DOUBLE_EQ(even.whisker_high, 4.0);
  EXPECT_TRUE(even.outliers.empty());
  const BoxSummary tail = SummarizeBox({4.0, 1.0, 100.0, 3.0, 2.0, std::nan("")});
  EXPECT_DOUBLE_EQ(tail.q1, 2.0);
  EXPECT_DOUBLE_EQ(tail.median, 3.0);
  EXPECT_DOUBLE_EQ(tail.q3, 4.0);
  EXPECT_DOUBLE_EQ(tail.whisker_low, 1.0);
  EXPECT_DOUBLE_EQ(tail.whisker_high, 4.0);
  EXPECT_EQ(tail.outliers, std::vector<double>{100.0});
  // One panel per preset, one box per estimator, diverged trials left out.
  BenchmarkResult result;
  result.estimators = {TorqueEstimator::kOls, TorqueEstimator::kDidim};
  result.presets = {NoisePreset::kLow, NoisePreset::kHigh};
  for (NoisePreset preset : result.presets) {
    for (int t = 0; t < 4; ++t) {
      BenchmarkTrial trial;
      trial.preset = preset;
      trial.trial = t;
      BenchmarkEstimate ols, didim;
      ols.parameter_error = 0.01 * (t + 1);
      didim.estimator = TorqueEstimator::kDidim;
      didim.parameter_error = 7.0;
      didim.diverged = t == 0;
      trial.estimates = {ols, didim};
      result.trials_run.push_back(trial);
    }
  }
  const PlotFigure figure = BenchmarkErrorPlot(result);
  ASSERT_EQ(figure.axes.size(), 2u);
  EXPECT_EQ(figure.axes[1].title, "noise preset high");
  EXPECT_EQ(figure.axes[0].categories, (std::vector<std::string>{"ols", "didim"}));
  const PlotSeries& boxes = figure.axes[0].series.at(0);
  EXPECT_DOUBLE_EQ(boxes.y[0], 0.0175);  // OLS's first quartile of 0.01 … 0.04
  EXPECT_FALSE(RenderPlot(figure, PlotFormat::kPng).empty());
}

}  // namespace
}  // namespace idbench
