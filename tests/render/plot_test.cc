#include "idbench/render/plot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "idbench/render/png_codec.h"

namespace idbench {
namespace {

TEST(PlotTicksTest, LinearTicksAreNiceStepsCoveringTheRange) {
  // Range 1.15 in about 6 steps: 0.19 rounds up to 0.2.
  const std::vector<double> ticks = LinearTicks(-0.13, 1.02, 6);
  const std::vector<double> expected{0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  ASSERT_EQ(ticks.size(), expected.size());
  for (size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-15);
  // In about 5 steps: 0.23 rounds up to 0.5.
  EXPECT_EQ(LinearTicks(-0.13, 1.02, 5), (std::vector<double>{0.0, 0.5, 1.0}));
  const std::vector<double> big = LinearTicks(-52000.0, 3000.0, 4);
  EXPECT_EQ(big.front(), -40000.0);
  EXPECT_EQ(big.back(), 0.0);
  EXPECT_TRUE(LinearTicks(1.0, 1.0, 4).empty());
}

TEST(PlotTicksTest, LogTicksArePowersOfTen) {
  EXPECT_EQ(LogTicks(1e-3, 1e2), (std::vector<double>{1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2}));
  // Wide ranges are thinned to about 8 labels.
  EXPECT_LE(LogTicks(1e-16, 1e4).size(), 11u);
  EXPECT_TRUE(LogTicks(0.0, 1.0).empty());
}

PlotFigure Example() {
  PlotFigure figure;
  figure.width = 400, figure.height = 300;
  PlotAxes axes;
  axes.title = "sine";
  axes.x_label = "t [s]";
  axes.y_label = "q [rad]";
  PlotSeries s;
  s.label = "q1";
  for (int i = 0; i <= 100; ++i) s.x.push_back(i * 0.01), s.y.push_back(std::sin(6.28 * i * 0.01));
  axes.series.push_back(s);
  figure.axes.push_back(axes);
  return figure;
}

TEST(PlotTest, OneDrawingGivesPngSvgAndPdf) {
  const PlotFigure figure = Example();
  const Image png = DecodePng(RenderPlot(figure, PlotFormat::kPng));
  EXPECT_EQ(png.width, 400);
  EXPECT_EQ(png.height, 300);
  // Not blank: the line's blue (Tableau 10's first colour) is there.
  int blue = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) blue += png.at(x, y)[2] > 150 && png.at(x, y)[0] < 100;
  EXPECT_GT(blue, 300);
  const std::string svg = RenderPlot(figure, PlotFormat::kSvg);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("400pt"), std::string::npos);
  const std::string pdf = RenderPlot(figure, PlotFormat::kPdf);
  EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
  EXPECT_NE(pdf.find("%%EOF", pdf.size() - 16), std::string::npos);
  // Deterministic raster.
  EXPECT_EQ(RenderPlot(figure, PlotFormat::kPng), RenderPlot(figure, PlotFormat::kPng));
}

TEST(PlotTest, RejectsBadSizesAndExtensions) {
  PlotFigure figure = Example();
  figure.width = 0;
  EXPECT_THROW(RenderPlot(figure, PlotFormat::kPng), std::invalid_argument);
  EXPECT_EQ(PlotFormatForPath("a/b.svg"), PlotFormat::kSvg);
  EXPECT_EQ(PlotFormatForPath("x.pdf"), PlotFormat::kPdf);
  EXPECT_THROW(PlotFormatForPath("x.jpg"), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
