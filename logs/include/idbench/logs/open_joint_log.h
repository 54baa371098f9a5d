// Opens a joint log wherever one is accepted, by what the path is: a CSV file
// today; log descriptions and rosbag2 bags plug in here (issue 24).
#pragma once

#include <memory>
#include <string>

#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"

namespace idbench {

// The log at `path` for `model`, read as `format` and `torques` say. Throws
// std::invalid_argument naming the path for an unreadable or malformed file
// (as ReadRecordedJointLog).
std::unique_ptr<JointLogSource> OpenJointLog(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques);

// Whether `path` is what a robot recorded rather than a motion to follow: a
// ROS 2 bag, a log description (.yaml, .yml, or a .json object with "files"),
// or a CSV file whose header names torque or current columns (tau<j>, i<j>,
// taum<j>, im<j>, or tau.<joint> ...). Reads at most a .json file (within
// MaxInputFileBytes) or a CSV file's first line; false for anything it cannot
// read (the reader that opens it then says why).
bool IsRecordedJointLogPath(const std::string& path);

}  // namespace idbench
