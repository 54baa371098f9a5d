// A transmission (transmission.h) named as simulate's and design's
// `transmission` field names it: "urdf" for the robot URDF's ros_control
// <transmission> elements, else a JSON or YAML file holding a log
// description with a "transmission", or the transmission alone
// ({"reduction": [N1, ...]} or {"actuator_from_joint": [[...], ...],
// "joint_offset": [...]}).
#pragma once

#include <optional>
#include <string>

#include "idbench/engine/transmission.h"

namespace idbench {

// nullopt when spec is empty; "urdf": from_urdf (the robot file's, as
// LoadRobot read it), or std::invalid_argument naming `robot` when it has
// none; else the file's. Throws std::invalid_argument naming the field
// `transmission`, or the file and its key, and checks it against n_dof.
std::optional<Transmission> ReadTransmissionArg(const std::string& spec, const std::string& robot, int n_dof,
                                                const std::optional<Transmission>& from_urdf);

}  // namespace idbench
