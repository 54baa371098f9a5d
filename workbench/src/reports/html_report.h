// The report as one HTML page (report_command.h) naming its figures and
// plots relatively.
#pragma once

#include <string>

#include "idbench/workbench/reports/report_command.h"

namespace idbench::internal {

// report.html: the title, the command, the experiment, figure.png, the
// tables, and each plot as SVG with links to its PNG and PDF.
std::string FormatHtml(const ReportContent& content);

}  // namespace idbench::internal
