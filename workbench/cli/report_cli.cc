// `idbench report --out DIR`: report.html and report.pdf for the results of
// `idbench run` in DIR (its results.json says how it ran).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/paper6r.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/commands/run_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench::cli {
namespace {

int ReportCommand(const std::string& out_dir, const CliContext& context) {
  if (out_dir.empty()) return context.UsageError("--out: empty path");
  const std::filesystem::path dir(out_dir);
  const std::filesystem::path results = dir / "results.json";
  if (!std::filesystem::is_regular_file(results)) {
    throw std::invalid_argument(results.string() + ": no such file; `idbench report` reads the results.json of " +
                                "`idbench run --out " + out_dir + "` (for identify, use `idbench identify --report`)");
  }
  RunOptions options = RunOptionsFromResultsJson(ReadInputFile(results), results.string());
  options.out_dir = out_dir;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(results.string() + ": " + why);
  const RobotModel model = MakePaper6r();
  const RunReport report = RunExperiment(model, options);
  const ReportContent content = MakeRunReportContent(model, options, report, RenderRunFigurePng(model, options));
  WriteFilesAtomically(FormatReportFiles(content, dir));
  std::printf("wrote %s and %s\n", (dir / "report.html").c_str(), (dir / "report.pdf").c_str());
  return 0;
}

}  // namespace

CliCommand AddReportCommand(CLI::App* app, CliContext* context) {
  auto out_dir = std::make_shared<std::string>();
  CLI::App* command = app->add_subcommand(
      "report", "Write report.html and report.pdf (figure, tables, plots) for the results of `idbench run` in DIR");
  AddOutFlag(command, out_dir.get(), "Directory holding results.json; the report is written there")->required();
  return {command, [out_dir, context] { return ReportCommand(*out_dir, *context); }};
}

}  // namespace idbench::cli
