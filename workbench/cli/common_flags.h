// The flags several commands share, each declared once here: --robot with
// --lock/--tip (how a URDF robot file becomes a chain), --out, --seed,
// --friction and --report. A command passes its own help text where its
// meaning differs (montecarlo's --out is optional, design's --seed seeds
// starts, not noise).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/enum_names.h"
#include "idbench/engine/robot_library.h"
#include "idbench/engine/urdf.h"

namespace idbench::cli {

inline constexpr const char* kRobotHelp = "Built-in robot (paper6r, puma560) or URDF file";
inline constexpr const char* kOutDirHelp = "Output directory (created if missing, never wiped)";
inline constexpr const char* kReportHelp = "Also write report.html, report.pdf and the plots";

// --robot NAME|FILE, its default shown.
CLI::Option* AddRobotFlag(CLI::App* command, std::string* robot, const std::string& help = kRobotHelp);

// --lock JOINT=VALUE (repeatable, or comma-separated) and --tip LINK: how a
// URDF robot file becomes a chain (see idbench/engine/urdf.h). For every
// subcommand that loads its --robot with LoadRobotOrThrow.
void AddRobotLoadFlags(CLI::App* command, UrdfLoadOptions* load);

// --robot and --lock/--tip, the first flags of most commands.
void AddRobotFlags(CLI::App* command, std::string* robot, UrdfLoadOptions* load, const std::string& help = kRobotHelp);

// A robot by name or path; warnings go to stderr. Throws UsageException for
// --lock/--tip with a built-in robot; what LoadRobot throws otherwise.
// transmission (optional): gets the URDF's <transmission> reductions.
RobotModel LoadRobotOrThrow(const std::string& name_or_path, const UrdfLoadOptions& load,
                            std::optional<Transmission>* transmission = nullptr);

// --out PATH (a directory or a file: the help says which). The caller shows
// the default (capture_default_str) or requires it.
CLI::Option* AddOutFlag(CLI::App* command, std::string* out, const std::string& help = kOutDirHelp);

// --seed N, its default shown.
CLI::Option* AddSeedFlag(CLI::App* command, unsigned* seed, const std::string& help = "Noise seed");

// --friction TERM,... (comma-separated), its default shown.
CLI::Option* AddFrictionFlag(CLI::App* command, std::vector<std::string>* friction, const std::string& help);

// --base-pose x,y,z,roll,pitch,yaw: the robot's base in the world (gravity
// along the world's −z), into *pose.
CLI::Option* AddBasePoseFlag(CLI::App* command, BasePose* pose);

// --scene FILE: the cell's JSON (floor, obstacles; scene_file.h).
CLI::Option* AddSceneFlag(CLI::App* command, std::string* scene);

// --report: also the HTML/PDF report and its plots.
CLI::Option* AddReportFlag(CLI::App* command, bool* report);

// A flag naming one value of an enum (`names`: enum_names.h), parsed into
// *value; a bad name is a usage error naming the field and the choices
// (flag-spelled as every message is). The default shown is *value's name.
template <typename Enum, std::size_t N>
CLI::Option* AddEnumFlag(CLI::App* command, const std::string& flag, Enum* value, const EnumNames<Enum, N>& names,
                         const std::string& help) {
  return command
      ->add_option_function<std::string>(
          flag,
          [value, &names](const std::string& text) {
            std::string why;
            if (!names.Parse(text, value, &why)) throw CLI::ValidationError(why);
          },
          help)
      ->default_str(std::string(names.Name(*value)));
}

// The same for an optional value (nullopt: the library's default, not shown).
template <typename Enum, std::size_t N>
CLI::Option* AddEnumFlag(CLI::App* command, const std::string& flag, std::optional<Enum>* value,
                         const EnumNames<Enum, N>& names, const std::string& help) {
  return command->add_option_function<std::string>(
      flag,
      [value, &names](const std::string& text) {
        std::string why;
        Enum parsed{};
        if (!names.Parse(text, &parsed, &why)) throw CLI::ValidationError(why);
        *value = parsed;
      },
      help);
}

}  // namespace idbench::cli
