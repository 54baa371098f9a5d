#include "idbench/workbench/reports/report_command.h"

#include "html_report.h"
#include "pdf_report.h"

namespace idbench {

using internal::FormatHtml;
using internal::FormatPdf;

std::vector<std::pair<std::filesystem::path, std::string>> FormatReportFiles(const ReportContent& content,
                                                                             const std::filesystem::path& dir) {
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  files.emplace_back(dir / "report.html", FormatHtml(content));
  files.emplace_back(dir / "report.pdf", FormatPdf(content));
  if (!content.pose_figure_png.empty()) files.emplace_back(dir / "figure.png", content.pose_figure_png);
  for (const ReportPlot& plot : content.plots) {
    const std::string stem = "plot_" + plot.stem;
    files.emplace_back(dir / (stem + ".png"), RenderPlot(plot.figure, PlotFormat::kPng));
    files.emplace_back(dir / (stem + ".svg"), RenderPlot(plot.figure, PlotFormat::kSvg));
    files.emplace_back(dir / (stem + ".pdf"), RenderPlot(plot.figure, PlotFormat::kPdf));
  }
  return files;
}

}  // namespace idbench
