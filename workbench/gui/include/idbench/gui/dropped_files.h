// Files dropped onto the window, routed by what they are: a robot (URDF) to
// the robot fields, a log to the Log tab's log or held-out log, anything else
// to a message naming the file and what is accepted. Plain functions: the
// GLFW drop callback, the script verb `drop` and the tests share them.
#pragma once

#include <string>
#include <vector>

namespace idbench::gui {

enum class DroppedKind { kRobot, kLog, kOther };

// By the path alone (and whether it is a bag folder): .urdf / .xacro a robot;
// .csv / .txt / .tsv, a log description (.json, .yaml, .yml), a rosbag2 bag
// (.db3, .mcap, or a folder with metadata.yaml) a log; anything else other.
// Extensions are matched without regard to case.
DroppedKind ClassifyDroppedPath(const std::string& path);

// Where one dropped file goes.
struct DroppedFileRoute {
  enum class Target { kRobot, kData, kValidate, kNone };
  std::string path;
  Target target = Target::kNone;
  std::string message;  // for the Messages panel: what was done, or why nothing
};

// Routes a drop of `paths` (in the order given). Robots go to kRobot (the last
// one loads). Logs fill the log (IdentifyOptions::data) then the held-out log
// (IdentifyOptions::validate); with `held_out` (Shift held while dropping)
// and a log already set, the first log goes to the held-out log instead. A
// log beyond those two, and anything that is not a robot or a log, is kNone.
std::vector<DroppedFileRoute> RouteDroppedFiles(const std::vector<std::string>& paths, bool data_set,
                                                bool held_out);

}  // namespace idbench::gui
