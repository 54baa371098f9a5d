// `idbench run`: the paper's experiment on paper6r (simulate, identify,
// compare with the truth); its flags fill RunOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_command.h"
#include "common_flags.h"
#include "output_files.h"
#include "idbench/engine/paper6r.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/commands/run_command.h"
#include "idbench/logs/simulation_log_csv.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench::cli {
namespace {

// Fields of RunOptions named in messages (beside the shared ones).
constexpr FieldFlag kRunSpellings[] = {{"motion", "--motion"}, {"accel_deg_s2", "--accel"}, {"sample_times", "--samples"}};

struct RunFlags {
  RunOptions options;
  bool no_figure = false;  // --no-figure: options.figure = false
};

int RunCommand(const RunOptions& options, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = MakePaper6r();
  const RunReport report = RunExperiment(model, options);
  std::fputs(FormatRunTables(options, report).c_str(), stdout);
  OutputFiles out(options.out_dir);
  out.Add("log.csv", FormatLogCsv(model, report.log));
  out.Add("results.json", FormatRunResultsJson(options, report));
  if (options.report) {
    out.AddReport(MakeRunReportContent(model, options, report, RenderRunFigurePng(model, options)));
  } else if (options.figure) {
    out.Add("figure.png", RenderRunFigurePng(model, options));
  }
  out.Write("wrote " + out.Path("results.json").string() + " and " + out.Path("log.csv").string() +
            (options.figure || options.report ? " and " + out.Path("figure.png").string() : "") +
            (options.report ? " and " + out.Path("report.html").string() + ", report.pdf" : ""));
  return 0;
}

}  // namespace

CliCommand AddRunCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kRunSpellings);
  auto flags = std::make_shared<RunFlags>();
  RunOptions& run = flags->options;
  run.command_line = context->command_line();
  CLI::App* command =
      app->add_subcommand("run", "Run the paper's experiment: simulate, identify, compare with the truth");
  AddRobotFlag(command, &run.robot, "Robot (built-in: paper6r)");
  command->add_option("--motion,--trajectory", run.motion,
                      "paper: hinges 1, 2 accelerate, others locked; general: all six move; or a .json/.csv file")
      ->capture_default_str();
  command->add_option("--accel", run.accel_deg_s2, "Hinge acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  command->add_option("--duration", run.duration, "Simulated time [s]")->capture_default_str();
  command->add_option("--dt", run.dt, "Simulation step [s]")->capture_default_str();
  CLI::Option* samples =
      command->add_option("--samples", run.sample_times, "Sample times t1,t2,... [s]")->delimiter(',');
  command->add_flag("--all-samples", run.all_samples, "Identify from every simulation step")->excludes(samples);
  AddOutFlag(command, &run.out_dir)->capture_default_str();
  command->add_flag("--no-figure", flags->no_figure, "Do not render figure.png (the poses at the paper's instants)");
  AddReportFlag(command, &run.report);
  return {command, [flags, context] {
            flags->options.figure = !flags->no_figure;
            return RunCommand(flags->options, *context);
          }};
}

}  // namespace idbench::cli
