// Joint limits for the excitation design (--limits FILE), in SI units:
//   {"joints": [{"q_min": rad, "q_max": rad, "qd_max": rad/s,
//                "qdd_max": rad/s², "tau_max": N m}, …]}
// one entry per joint in order; an omitted value comes from the robot file.
// Optionally, limits on the motor side of a transmission (actuator_limits.h):
//   "actuators": [{"qd_max": rad/s of the motor, "tau_max": N m}, …]
// one entry per motor; an omitted value is no limit.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/excitation/actuator_limits.h"

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

// The limits JSON's "actuators" (empty when it has none). Throws
// std::invalid_argument "source: actuators[k].key: what" as ParseLimitsJson
// does; the count is checked against the transmission (ActuatorLimits::Check).
std::vector<ActuatorLimit> ParseActuatorLimitsJson(const std::string& text, const std::string& source);
std::vector<ActuatorLimit> ReadActuatorLimitsFile(const std::string& path);

}  // namespace idbench
