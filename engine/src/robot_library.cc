#include "idbench/engine/robot_library.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"

namespace idbench {

std::vector<std::string> BuiltinRobotNames() { return {"paper6r", "puma560"}; }

UrdfLoadResult LoadRobot(const std::string& name_or_path, const UrdfLoadOptions& options) {
  const std::vector<std::string> builtins = BuiltinRobotNames();
  if (!options.empty() && std::find(builtins.begin(), builtins.end(), name_or_path) != builtins.end()) {
    throw std::invalid_argument("robot '" + name_or_path +
                                "': locked_joints and tip_link apply to URDF files only, not to a built-in robot");
  }
  if (name_or_path == "paper6r") return {MakePaper6r(), {}, {}};
  if (name_or_path == "puma560") return {MakePuma560(), InertiaWarnings(MakePuma560()), {}};
  if (std::filesystem::exists(name_or_path)) return LoadUrdfFile(name_or_path, options);
  std::string names;
  for (const std::string& n : BuiltinRobotNames()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("robot '" + name_or_path + "': neither a built-in robot (" + names +
                              ") nor an existing URDF file");
}

}  // namespace idbench
