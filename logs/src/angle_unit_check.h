// A check of a recorded log against its format's angle unit.
#pragma once

#include <string>

#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/recorded_joint_log.h"

namespace idbench::internal {

// With angle_unit "deg", a log whose every joint moves less than
// kSmallMotionDeg is most likely in radians (a motion of 2 rad read as 2°):
// a warning, since a log of small motions in degrees is possible.
void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, RecordedJointLog* out);

}  // namespace idbench::internal
