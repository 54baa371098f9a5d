#include "html_report.h"

#include "idbench/engine/urdf.h"

namespace idbench {

std::string EscapeHtml(const std::string& text) { return EscapeXml(text); }

namespace internal {

std::string FormatHtml(const ReportContent& content) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + EscapeHtml(content.title) +
      "</title>\n<style>\n"
      "body{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;"
      "color:#222}\n"
      "pre{background:#f4f4f6;padding:.6em;white-space:pre-wrap;word-break:break-all}\n"
      "table{border-collapse:collapse;font-size:.85em;margin:.5em 0 1.5em}\n"
      "th,td{border:1px solid #ccc;padding:.2em .5em;text-align:right}\n"
      "th{background:#eee}td:first-child,td:nth-child(2){text-align:left}\n"
      "img{max-width:100%}figure{margin:1em 0}figcaption{font-size:.9em;color:#444}\n"
      "</style>\n</head>\n<body>\n";
  html += "<h1>" + EscapeHtml(content.title) + "</h1>\n";
  html += "<p>Reproduce with:</p>\n<pre>" + EscapeHtml(content.command) + "</pre>\n";
  html += "<p>The same report as <a href=\"report.pdf\">PDF</a>.</p>\n<h2>Experiment</h2>\n<table>\n";
  for (const auto& [key, value] : content.experiment) {
    html += "<tr><td>" + EscapeHtml(key) + "</td><td>" + EscapeHtml(value) + "</td></tr>\n";
  }
  html += "</table>\n";
  if (!content.pose_figure_png.empty()) {
    html += "<figure><img src=\"figure.png\" alt=\"poses\"><figcaption>" + EscapeHtml(content.pose_caption) +
            "</figcaption></figure>\n";
  }
  for (const ReportTable& table : content.tables) {
    html += "<h2>" + EscapeHtml(table.caption) + "</h2>\n<table>\n<tr>";
    for (const std::string& h : table.header) html += "<th>" + EscapeHtml(h) + "</th>";
    html += "</tr>\n";
    for (const auto& row : table.rows) {
      html += "<tr>";
      for (const std::string& cell : row) html += "<td>" + EscapeHtml(cell) + "</td>";
      html += "</tr>\n";
    }
    html += "</table>\n";
  }
  html += "<h2>Plots</h2>\n";
  for (const ReportPlot& plot : content.plots) {
    const std::string file = "plot_" + plot.stem;
    html += "<figure><img src=\"" + file + ".svg\" alt=\"" + EscapeHtml(plot.caption) + "\"><figcaption>" +
            EscapeHtml(plot.caption) + " (<a href=\"" + file + ".png\">PNG</a>, <a href=\"" + file +
            ".pdf\">PDF</a>)</figcaption></figure>\n";
  }
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace internal
}  // namespace idbench
