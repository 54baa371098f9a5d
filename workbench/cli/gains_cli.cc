// `idbench gains`: drive gains (torque per motor current) from an unloaded
// log and one with a known payload; its flags fill GainsOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/gains_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {
namespace {

// Fields of GainsOptions named in messages.
constexpr FieldFlag kGainsSpellings[] = {{"loaded_time_window", "--loaded-time-window"},
                                         {"time_window", "--time-window"},
                                         {"data", "--data"},
                                         {"loaded", "--loaded"},
                                         {"payload_mass", "--payload-mass"}};

int GainsCommand(const GainsOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = LoadRobotOrThrow(options.robot, load);
  if (!options.preparation().format.IsValidFor(model.n_dof(), &why)) return context.UsageError(why);
  const GainsReport report = RunGains(model, options);
  context.PrintWarnings(report.warnings);
  std::fputs(FormatGainsTable(model, options, report).c_str(), stdout);
  if (report.estimate.status != DriveGainStatus::kEstimated) {  // the table above says why; nothing written
    std::fprintf(stderr, "idbench: error: %s\n", context.FlagSpelling(report.estimate.message).c_str());
    return kExitFailure;
  }
  const std::filesystem::path dir(options.out_dir);
  EnsureOutputDirectory(dir);
  WriteFileAtomically(dir / "gains.json", FormatGainsJson(model, options, report));
  std::printf("wrote %s\n", (dir / "gains.json").c_str());
  return 0;
}

}  // namespace

CliCommand AddGainsCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kGainsSpellings);
  context->AddSpellings(kLogReadingSpellings);
  auto options = std::make_shared<GainsOptions>();
  GainsOptions& gains = *options;
  gains.command_line = context->command_line();
  CLI::App* command = app->add_subcommand(
      "gains", "Drive gains (torque per motor current) from an unloaded log and one with a known payload mass");
  AddRobotFlags(command, &gains.robot, context->robot_load());
  command->add_option("--data", gains.data, "Unloaded log with motor currents i1..in")->required();
  command->add_option("--loaded", gains.loaded, "Log of the same robot with the payload on the last link")->required();
  command->add_option("--payload-mass", gains.payload_mass, "Known payload mass [kg]")->required();
  AddLogReadingFlags(command, &gains.format, &gains.friction, {&gains.coulomb_smoothing, &gains.coulomb_min_speed},
                     &gains.filter, &gains.max_gap_s);
  command->add_option("--time-window", gains.time_window, "Use only T0 <= t <= T1 of --data: T0,T1 [s]")
      ->delimiter(',');
  command->add_option("--loaded-time-window", gains.loaded_time_window, "Use only T0 <= t <= T1 of --loaded: T0,T1 [s]")
      ->delimiter(',');
  AddOutFlag(command, &gains.out_dir, "Output directory for gains.json (created if missing, never wiped)")
      ->capture_default_str();
  return {command, [options, context] { return GainsCommand(*options, *context->robot_load(), *context); }};
}

}  // namespace idbench::cli
