// report.html (html_report.h) as a library call: the page holds the content
// it was given, escaped, in order: title, command, experiment rows, the pose
// figure, every table cell, and each plot as SVG with its PNG and PDF links;
// and for a real run, every identified value as the report content formats it.
#include "html_report.h"

#include <gtest/gtest.h>

#include <string>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using internal::FormatHtml;

size_t Count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

ReportContent Content() {
  ReportContent content;
  content.title = "idbench run: <robot> & co";
  content.command = "idbench run --motion \"my file.json\"";
  content.experiment = {{"robot", "paper6r"}, {"duration, step", "2 s, 0.001 s"}};
  content.pose_figure_png = "png";
  content.pose_caption = "The poses (a) … (h)";
  content.tables = {{"Errors", {"body", "rel error"}, {{"B1", "1.25e-04"}, {"B2", "-"}, {"B3", "3.00e-06"}}},
                    {"Blocks", {"body", "rank"}, {{"B1", "3/4"}}}};
  content.plots = {{"joints", "Joint <signals>", PlotFigure{}}, {"spectrum", "Spectrum", PlotFigure{}}};
  return content;
}

TEST(HtmlReportTest, PageHoldsTheContentEscapedAndInOrder) {
  const std::string html = FormatHtml(Content());
  EXPECT_EQ(html.substr(0, 15), "<!DOCTYPE html>");
  EXPECT_EQ(html.substr(html.size() - 16), "</body>\n</html>\n");
  const std::string parts[] = {
      "<title>idbench run: &lt;robot&gt; &amp; co</title>",
      "<h1>idbench run: &lt;robot&gt; &amp; co</h1>\n",
      "<pre>idbench run --motion &quot;my file.json&quot;</pre>\n",
      "<a href=\"report.pdf\">PDF</a>",
      "<tr><td>robot</td><td>paper6r</td></tr>\n<tr><td>duration, step</td><td>2 s, 0.001 s</td></tr>\n",
      "<figure><img src=\"figure.png\" alt=\"poses\"><figcaption>The poses (a) … (h)</figcaption></figure>\n",
      "<h2>Errors</h2>\n<table>\n<tr><th>body</th><th>rel error</th></tr>\n"
      "<tr><td>B1</td><td>1.25e-04</td></tr>\n<tr><td>B2</td><td>-</td></tr>\n<tr><td>B3</td><td>3.00e-06</td></tr>\n"
      "</table>\n",
      "<h2>Blocks</h2>\n<table>\n<tr><th>body</th><th>rank</th></tr>\n<tr><td>B1</td><td>3/4</td></tr>\n</table>\n",
      "<h2>Plots</h2>\n",
      "<figure><img src=\"plot_joints.svg\" alt=\"Joint &lt;signals&gt;\"><figcaption>Joint &lt;signals&gt; (<a "
      "href=\"plot_joints.png\">PNG</a>, <a href=\"plot_joints.pdf\">PDF</a>)</figcaption></figure>\n",
      "<img src=\"plot_spectrum.svg\"",
  };
  size_t at = 0;
  for (const std::string& part : parts) {
    const size_t found = html.find(part, at);
    ASSERT_NE(found, std::string::npos) << "missing or out of order:\n" << part << "\nin\n" << html;
    at = found + part.size();
  }
  // Nothing raw slips through: the only '<' and '>' are the tags'.
  EXPECT_EQ(html.find("<robot>"), std::string::npos);
  EXPECT_EQ(html.find("<signals>"), std::string::npos);
  // Two tables of content plus the experiment's; two plots; one pose figure.
  EXPECT_EQ(Count(html, "<table>"), 3u);
  EXPECT_EQ(Count(html, "<tr><td>"), 2u + 3u + 1u);
  EXPECT_EQ(Count(html, "<figure>"), 3u);

  ReportContent bare = Content();
  bare.pose_figure_png.clear();
  bare.plots.clear();
  const std::string plain = FormatHtml(bare);
  EXPECT_EQ(plain.find("figure.png"), std::string::npos);
  EXPECT_EQ(Count(plain, "<figure>"), 0u);
  EXPECT_NE(plain.find("<h2>Plots</h2>\n</body>"), std::string::npos);
}

// A real run's page: every cell of the parameter table appears in a <td>,
// e.g. each identified value to 12 significant digits.
TEST(HtmlReportTest, RunPageHoldsEveryIdentifiedValue) {
  const RobotModel model = MakePaper6r();
  const RunOptions options;
  const RunReport report = RunExperiment(model, options);
  const std::string html = FormatHtml(MakeRunReportContent(model, options, report, ""));
  int n_checked = 0;
  for (const BodyResult& body : report.identification.bodies) {
    for (const ParameterResult& p : body.parameters) {
      if (!p.identifiable) {
        EXPECT_NE(html.find("<td>" + body.name + "</td><td>" + p.name + "</td>"), std::string::npos) << p.name;
        continue;
      }
      char identified[64];
      std::snprintf(identified, sizeof identified, "%.12g", p.identified);
      EXPECT_NE(html.find("<td>" + body.name + "</td><td>" + p.name + "</td>"), std::string::npos) << p.name;
      EXPECT_NE(html.find("<td>" + std::string(identified) + "</td>"), std::string::npos) << p.name << " " << identified;
      ++n_checked;
    }
  }
  EXPECT_GE(n_checked, 30);
  EXPECT_EQ(html.find("figure.png"), std::string::npos);  // no pose figure given
  EXPECT_EQ(Count(html, "<tr><td>B"), 42u + 6u);           // parameters and blocks
}

}  // namespace
}  // namespace idbench
