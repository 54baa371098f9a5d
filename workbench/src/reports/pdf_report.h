// The report as a PDF: A4 pages drawn with cairo (report_command.h).
#pragma once

#include <string>

#include "idbench/workbench/reports/report_command.h"

namespace idbench::internal {

// The title, the command, the experiment, the pose figure, the tables and
// the plots, page after page. Throws std::runtime_error if cairo fails.
std::string FormatPdf(const ReportContent& content);

}  // namespace idbench::internal
