#include "idbench/gui/dropped_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "idbench/logs/joint_log_description.h"
#include "idbench/logs/rosbag2_joint_log.h"

namespace idbench::gui {

DroppedKind ClassifyDroppedPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".urdf" || ext == ".xacro") return DroppedKind::kRobot;
  if (ext == ".csv" || ext == ".txt" || ext == ".tsv" || ext == ".db3" || ext == ".mcap") return DroppedKind::kLog;
  if (IsRosbag2Path(path) || IsJointLogDescriptionPath(path)) return DroppedKind::kLog;
  return DroppedKind::kOther;
}

std::vector<DroppedFileRoute> RouteDroppedFiles(const std::vector<std::string>& paths, bool data_set,
                                                bool held_out) {
  using Target = DroppedFileRoute::Target;
  // The slots logs fill, in order.
  std::vector<Target> slots = held_out && data_set ? std::vector<Target>{Target::kValidate}
                                                   : std::vector<Target>{Target::kData, Target::kValidate};
  size_t next_slot = 0;
  std::vector<DroppedFileRoute> routes;
  for (const std::string& path : paths) {
    DroppedFileRoute route;
    route.path = path;
    const std::string name = "'" + std::filesystem::path(path).filename().string() + "'";
    switch (ClassifyDroppedPath(path)) {
      case DroppedKind::kRobot:
        route.target = Target::kRobot;
        route.message = "dropped " + name + ": the robot (" + path + ")";
        break;
      case DroppedKind::kLog:
        if (next_slot < slots.size()) {
          route.target = slots[next_slot++];
          route.message = "dropped " + name + ": the " +
                          (route.target == Target::kData ? "log" : "held-out log") + " (" + path + ")";
        } else {
          route.message = "dropped " + name + ": ignored, a drop sets at most a log and a held-out log";
        }
        break;
      case DroppedKind::kOther:
        route.message = "dropped " + name + ": not a robot or a log; accepted are a URDF (.urdf, .xacro) and a "
                        "log (.csv, .txt, .tsv, a description .json/.yaml, a rosbag2 .db3/.mcap or bag folder)";
        break;
    }
    routes.push_back(route);
  }
  return routes;
}

}  // namespace idbench::gui
