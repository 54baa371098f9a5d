// `idbench payload`: a payload's mass, centre of mass and inertia from a log
// with it (and an unloaded one); its flags fill PayloadOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/payload_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {
namespace {

// Fields of PayloadOptions named in messages.
constexpr FieldFlag kPayloadSpellings[] = {{"unloaded_time_window", "--unloaded-time-window"},
                                           {"time_window", "--time-window"},
                                           {"loaded_log", "--data"},
                                           {"unloaded_log", "--unloaded"},
                                           {"payload_link", "--link"},
                                           {"max_relative_sigma", "--max-relative-sigma"},
                                           {"max_projection_distance", "--max-projection-distance"},
                                           {"write_unverified", "--write-unverified"},
                                           {"out_dir", "--out"}};

int PayloadCommand(const PayloadOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  // Mounted as base_pose says (gravity in its base frame), as identify does.
  const RobotModel model = MountRobot(LoadRobotOrThrow(options.robot, load), options.base_pose);
  if (!options.IsValidFor(model, &why)) return context.UsageError(why);
  const PayloadSummary summary = RunPayload(model, options);
  context.PrintWarnings(summary.warnings);
  std::fputs(FormatPayloadTable(options, summary).c_str(), stdout);
  // payload.json always (the diagnostics); payload.urdf.xml only for a good
  // verdict, or when the user accepts it (--write-unverified).
  EnsureOutputDirectory(options.out_dir);
  const auto files = PayloadFiles(model, options, summary);
  WriteFilesAtomically(files);
  std::string written;
  for (const auto& [path, text] : files) written += (written.empty() ? "" : " and ") + path.string();
  std::printf("wrote %s\n", written.c_str());
  if (summary.good()) return 0;
  if (options.write_unverified && WritesPayloadUrdf(options, summary)) {
    std::fprintf(stderr, "idbench: warning: %s (payload.urdf.xml written anyway, as asked)\n",
                 context.FlagSpelling(summary.message).c_str());
    return 0;
  }
  std::fprintf(stderr, "idbench: error: %s; payload.urdf.xml not written%s\n",
               context.FlagSpelling(summary.message).c_str(),
               summary.status == PayloadStatus::kNotIdentifiable ? "" : " (--write-unverified writes it anyway)");
  return kExitFailure;
}

}  // namespace

CliCommand AddPayloadCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kPayloadSpellings);
  context->AddSpellings(kLogReadingSpellings);
  auto options = std::make_shared<PayloadOptions>();
  PayloadOptions& payload = *options;
  payload.command_line = context->command_line();
  CLI::App* command = app->add_subcommand(
      "payload", "Mass, centre of mass and inertia of a payload on an identified robot, from a log with it");
  AddRobotFlags(command, &payload.robot, context->robot_load(),
                "The identified robot: URDF file (e.g. identify's identified.urdf) or built-in name");
  command->get_option("--robot")->required();
  command->add_option("--data", payload.loaded_log, "Joint log with the payload (t, q*, [qd*, qdd*], tau*)")
      ->required();
  command->add_option("--unloaded", payload.unloaded_log,
                      "Joint log of the same motion without the payload: cancels the robot file's errors");
  command->add_option("--link", payload.payload_link, "URDF link carrying the payload (default: the chain's last)");
  AddLogReadingFlags(command, &payload.format, &payload.friction,
                     {&payload.coulomb_smoothing, &payload.coulomb_min_speed}, &payload.filter, &payload.max_gap_s);
  AddDriveGainsFlag(command, &payload.format);
  AddBasePoseFlag(command, &payload.base_pose);
  command->add_option("--time-window", payload.time_window, "Use only T0 <= t <= T1 of --data: T0,T1 [s]")
      ->delimiter(',');
  command->add_option("--unloaded-time-window", payload.unloaded_time_window,
                      "Use only T0 <= t <= T1 of --unloaded: T0,T1 [s]")->delimiter(',');
  command->add_option("--max-relative-sigma", payload.max_relative_sigma,
                      "Verdict: each sigma at most this fraction of its scale (mass; |com| or radius of gyration; tr(I)/2)")->capture_default_str();
  command->add_option("--max-projection-distance", payload.max_projection_distance,
                      "Verdict: the physically consistent payload within this many sigma of the least-squares one")
      ->capture_default_str();
  command->add_flag("--write-unverified", payload.write_unverified,
                    "Write payload.urdf.xml even when the verdict is not good (every quantity determined; exit 0)");
  AddOutFlag(command, &payload.out_dir, "Output directory for payload.json and payload.urdf.xml (created if missing, "
             "never wiped)")->capture_default_str();
  return {command, [options, context] { return PayloadCommand(*options, *context->robot_load(), *context); }};
}

}  // namespace idbench::cli
