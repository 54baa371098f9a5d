// The joint-log CSV format (README.md, "Joint logs"): a header naming the
// columns, then one sample per line:
//   t, q1..qn, [qd1..qdn, qdd1..qddn,] tau1..taun
// Columns may come in any order; qd and qdd are optional (both or neither).
// Numbers are written in their shortest round-trip form.
#pragma once

#include <string>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

std::string FormatJointLogCsv(const JointLog& log);

// Parses a joint log of `model`. `source` names the file in messages. Throws
// std::invalid_argument with "source:line: column c ('name'): what" for: a
// missing, unknown or repeated column, a joint the robot does not have, a line
// with the wrong number of fields, a field that is not a finite number, time
// not strictly increasing, a position outside the joint's limits, or no data.
JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source);

// Reads and parses a file; an unreadable file throws naming the path.
JointLog ReadJointLogCsv(const std::string& path, const RobotModel& model);

}  // namespace idbench
