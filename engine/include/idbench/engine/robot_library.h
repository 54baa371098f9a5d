// Robots by name: the built-in models, or a URDF file by path.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/urdf.h"

namespace idbench {

// "paper6r", "puma560".
std::vector<std::string> BuiltinRobotNames();

// A built-in robot by name, else the URDF file at that path, read with
// `options` (see urdf.h). Throws std::invalid_argument naming the robot
// (unknown name, unreadable or unsupported file; see urdf.h; options given
// for a built-in robot). Warnings name links whose inertia is physically
// implausible but usable, and the joints locked off the chain.
UrdfLoadResult LoadRobot(const std::string& name_or_path, const UrdfLoadOptions& options = {});

}  // namespace idbench
