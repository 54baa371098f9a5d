// A check of a recorded log against its format's angle unit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "idbench/logs/joint_log_format.h"

namespace idbench::internal {

// With angle_unit "deg", a log whose every joint moves less than
// kSmallMotionDeg is most likely in radians (a motion of 2 rad read as 2°):
// a warning, since a log of small motions in degrees is possible.
// q: the log's joint positions as read (n_samples × n_dof); the warning,
// naming `source`, goes to *warnings.
void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, const Eigen::MatrixXd& q,
                                std::vector<std::string>* warnings);
// The same from each joint's range over the log [rad] (a running min and
// max kept while streaming) and the number of samples.
void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, const Eigen::VectorXd& q_min,
                                const Eigen::VectorXd& q_max, std::int64_t n_samples, std::vector<std::string>* warnings);

}  // namespace idbench::internal
