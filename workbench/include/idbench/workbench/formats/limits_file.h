// Joint limits for the excitation design (--limits FILE), in SI units:
//   {"joints": [{"q_min": rad, "q_max": rad, "qd_max": rad/s,
//                "qdd_max": rad/s², "tau_max": N m}, …]}
// one entry per joint in order; an omitted value comes from the robot file.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench {

// The robot file's limits, one per joint.
std::vector<JointLimits> RobotLimits(const RobotModel& model);

// The robot's limits overridden by a limits JSON text. Throws
// std::invalid_argument "source: joints[i].key: what" for invalid JSON, a
// wrong joint count, an unknown key, a value that is not a finite number, a
// limit ≤ 0 or q_min ≥ q_max.
std::vector<JointLimits> ParseLimitsJson(const std::string& text, const RobotModel& model, const std::string& source);

// Reads and parses a limits file; an unreadable file throws naming the path.
std::vector<JointLimits> ReadLimitsFile(const std::string& path, const RobotModel& model);

}  // namespace idbench
