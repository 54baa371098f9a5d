// `idbench compare`: the identifiability of motions side by side (cond, log
// det, %sigma, Monte-Carlo error on Bullet data); its flags fill CompareOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_command.h"
#include "common_flags.h"
#include "output_files.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/compare_command.h"
#include "idbench/workbench/reports/design_report.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench::cli {
namespace {

// Fields of CompareOptions named in messages.
constexpr FieldFlag kCompareSpellings[] = {{"model", "--model"},
                                           {"samples", "--samples"},
                                           {"trials", "--trials"},
                                           {"tau_noise", "--tau-noise"},
                                           {"wrench_noise", "--wrench-noise"},
                                           {"clearance", "--clearance"},
                                           {"given", "--given"}};

struct CompareFlags {
  CompareOptions options;
  bool report = false;   // --report
};

int CompareCommand(const CompareOptions& options, const UrdfLoadOptions& load, bool with_report,
                   const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = LoadRobotOrThrow(options.robot, load);
  const CompareReport report = RunCompare(model, options);
  context.PrintWarnings(report.warnings);  // how the logs were read, as identify prints it
  std::fputs(FormatCompareTable(options, report).c_str(), stdout);
  OutputFiles out(options.out_dir);
  out.Add("compare.json", FormatCompareJson(options, report));
  out.Add("compare.csv", FormatCompareCsv(report));
  if (with_report) out.AddReport(MakeCompareReportContent(options, report));
  out.Write("wrote " + out.Path("compare.json").string() + " and compare.csv" +
            (with_report ? ", report.html and report.pdf" : ""));
  return 0;
}

}  // namespace

CliCommand AddCompareCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kCompareSpellings);
  auto flags = std::make_shared<CompareFlags>();
  CompareOptions& compare = flags->options;
  compare.command_line = context->command_line();
  CLI::App* command = app->add_subcommand(
      "compare", "Identifiability of motions side by side: cond, log det, %sigma, Monte-Carlo error on Bullet data");
  command->add_option("trajectories", compare.trajectories, "Motions: built-in names or .json/.csv files");
  command->add_option("--log", compare.logs,
                      "A recorded joint log (CSV, log description, ROS 2 bag) compared beside the motions; repeatable")
      ->type_name("PATH");
  command
      ->add_option("--given", compare.given,
                   "A motion the robot already has (a joint log, or a designed trajectory); repeatable: the motions "
                   "are ranked by cond(W) of their union with these")
      ->type_name("PATH")
      ->allow_extra_args(false);
  AddRobotFlags(command, &compare.robot, context->robot_load(), "Built-in robot or URDF file");
  AddEnumFlag(command, "--model", &compare.model, kIdentificationModelNames, "torque or per-body");
  AddFrictionFlag(command, &compare.friction, "Friction terms of the torque model");
  command->add_option("--duration", compare.duration, "Length of built-in motions [s]")->capture_default_str();
  command->add_option("--samples", compare.samples, "Samples per motion")->capture_default_str();
  command->add_option("--tau-noise,--noise", compare.tau_noise,
                      "Torque noise sigma per joint, or one for all [N m] (torque model); default: 0.5 on joints 1-3, "
                      "0.05 on the others")
      ->delimiter(',');
  command->add_option("--wrench-noise", compare.wrench_noise, "Hinge force, moment noise sigma [N, N m] (per-body)")
      ->delimiter(',')->capture_default_str();
  AddSceneFlag(command, &compare.scene);
  AddBasePoseFlag(command, &compare.base_pose);
  command->add_option("--clearance", compare.clearance, "Minimum link clearance in the limits check [m]; -1: off")
      ->capture_default_str();
  command->add_option("--trials", compare.trials, "Monte-Carlo trials per motion")->capture_default_str();
  AddSeedFlag(command, &compare.seed);
  context->AddSpellings(kLogReadingSpellings);
  AddLogReadingFlags(command, &compare.format, nullptr, {}, &compare.filter, &compare.max_gap_s);
  AddDriveGainsFlag(command, &compare.format);
  AddOutFlag(command, &compare.out_dir, "Output directory for compare.json and compare.csv")->capture_default_str();
  AddReportFlag(command, &flags->report);
  return {command, [flags, context] {
            return CompareCommand(flags->options, *context->robot_load(), flags->report, *context);
          }};
}

}  // namespace idbench::cli
