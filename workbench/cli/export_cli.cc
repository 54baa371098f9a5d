// `idbench export`: an identification's robot model as MJCF or URDF, from its
// identified.json and the robot; its flags fill ExportOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/workbench/commands/export_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {
namespace {

// Fields of ExportOptions named in messages.
constexpr FieldFlag kExportSpellings[] = {
    {"identified", "--identified"}, {"format", "--format"}, {"write_unverified", "--write-unverified"}};

int ExportCommand(const ExportOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  // Loaded and mounted as identify loads it (the URDF's <transmission> for actuator-side terms).
  std::optional<Transmission> transmission;
  const RobotModel model = MountRobot(LoadRobotOrThrow(options.robot, load, &transmission), options.base_pose);
  const ExportReport report = RunExport(model, options, transmission);
  if (!report.writes) {  // the verdict refuses it: nothing written
    std::fprintf(stderr, "idbench: error: %s\n", context.FlagSpelling(report.refused).c_str());
    return kExitFailure;
  }
  if (!report.refused.empty()) std::fprintf(stderr, "idbench: warning: %s\n", context.FlagSpelling(report.refused).c_str());
  const std::filesystem::path dir(options.out_dir);
  EnsureOutputDirectory(dir);
  WriteFileAtomically(dir / options.file_name(), report.content);
  std::printf("wrote %s\n", (dir / options.file_name()).c_str());
  return 0;
}

}  // namespace

CliCommand AddExportCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kExportSpellings);
  auto options = std::make_shared<ExportOptions>();
  ExportOptions& exported = *options;
  CLI::App* command = app->add_subcommand(
      "export", "Write an identified robot as MJCF (identified.xml) or URDF from identify's identified.json");
  AddRobotFlags(command, &exported.robot, context->robot_load(), "The robot identified: built-in name or URDF path");
  AddBasePoseFlag(command, &exported.base_pose);
  command->add_option("--identified", exported.identified, "identified.json written by idbench identify")->required();
  AddEnumFlag(command, "--format", &exported.format, kExportFormatNames,
              "mjcf (identified.xml), urdf (identified.urdf) or yaml (joints.yaml)");
  command->add_flag("--write-unverified", exported.write_unverified,
                    "Write the model even when its verdict says it is not fit to load (exit 0)");
  AddOutFlag(command, &exported.out_dir, "Output directory for the file (created if missing, never wiped)")
      ->capture_default_str();
  return {command, [options, context] { return ExportCommand(*options, *context->robot_load(), *context); }};
}

}  // namespace idbench::cli
