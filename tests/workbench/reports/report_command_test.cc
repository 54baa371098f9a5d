// The report's files as a library call: FormatReportFiles gives report.html,
// report.pdf, figure.png and three files a plot, each named relatively in the
// HTML and none empty; EscapeHtml.
#include "idbench/workbench/reports/report_command.h"

#include <gtest/gtest.h>

#include <string>

namespace idbench {
namespace {

namespace fs = std::filesystem;

// A small content: a pose figure and one plot (the files do not depend on the rest).
ReportContent SmallContent() {
  PlotAxes axes;
  axes.series = {{"y = 2x", {0.0, 1.0, 2.0}, {0.0, 2.0, 4.0}, {}, PlotSeries::Style::kLine}};
  ReportContent content;
  content.title = "a < b & c";
  content.pose_figure_png = "\x89PNG not really";
  content.plots = {{"line", "A line.", PlotFigure{{axes}, 1, 200.0, 150.0}}};
  return content;
}

TEST(ReportCommandTest, FilesAreTheHtmlPdfFigureAndEachPlotInThreeFormats) {
  const fs::path dir = "some/dir";
  const auto files = FormatReportFiles(SmallContent(), dir);
  std::vector<std::string> names;
  for (const auto& [path, bytes] : files) {
    EXPECT_EQ(path.parent_path(), dir) << path;
    names.push_back(path.filename().string());
    EXPECT_GT(bytes.size(), 0u) << path;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"report.html", "report.pdf", "figure.png", "plot_line.png", "plot_line.svg",
                                             "plot_line.pdf"}));
  EXPECT_EQ(files[2].second, "\x89PNG not really");  // the figure as given
  EXPECT_EQ(files[1].second.substr(0, 5), "%PDF-");
  EXPECT_EQ(files[3].second.substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_NE(files[4].second.find("<svg"), std::string::npos);
  EXPECT_EQ(files[5].second.substr(0, 5), "%PDF-");
  // The HTML names the others relatively.
  const std::string& html = files[0].second;
  for (const char* name : {"\"report.pdf\"", "\"figure.png\"", "\"plot_line.svg\"", "\"plot_line.png\"", "\"plot_line.pdf\""}) {
    EXPECT_NE(html.find(name), std::string::npos) << name;
  }
  EXPECT_EQ(html.find("some/dir"), std::string::npos);

  // Without a pose figure and plots: the two reports alone, and no figure named.
  ReportContent bare = SmallContent();
  bare.pose_figure_png.clear();
  bare.plots.clear();
  const auto two = FormatReportFiles(bare, dir);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].first, dir / "report.html");
  EXPECT_EQ(two[1].first, dir / "report.pdf");
  EXPECT_EQ(two[0].second.find("figure.png"), std::string::npos);
}

TEST(ReportCommandTest, EscapeHtmlEscapesTheFourCharacters) {
  EXPECT_EQ(EscapeHtml("a < b & c > \"d\""), "a &lt; b &amp; c &gt; &quot;d&quot;");
  EXPECT_EQ(EscapeHtml("J22 [kg m²]"), "J22 [kg m²]");
  EXPECT_EQ(EscapeHtml(""), "");
}

}  // namespace
}  // namespace idbench
