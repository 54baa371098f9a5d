// The joint-log CSV format (README.md, "Joint logs"): a header naming the
// columns, then one sample per line:
//   t, q1..qn, [qd1..qdn, qdd1..qddn,] tau1..taun
// Columns may come in any order; qd and qdd are optional (both or neither).
// A trajectory file (trajectory_file.h) is the same format with tau optional.
// Numbers are written in their shortest round-trip form.
#pragma once

#include <string>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

// Writes the columns the log has: t, q, qd and qdd if present, tau if present.
std::string FormatJointLogCsv(const JointLog& log);

// Whether the tau columns must be there (a joint log) or may be absent (a
// trajectory: all of tau1..taun or none).
enum class TorqueColumns { kRequired, kOptional };

// Parses a joint log of `model`. `source` names the file in messages. Throws
// std::invalid_argument with "source:line: column c ('name'): what" for: a
// missing, unknown or repeated column, a joint the robot does not have, a line
// with the wrong number of fields, a field that is not a finite number, time
// not strictly increasing, a position outside the joint's limits, or no data.
// With TorqueColumns::kOptional and no tau columns, log.tau is empty (0 × 0).
JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source,
                          TorqueColumns torques = TorqueColumns::kRequired);

// Reads and parses a file; an unreadable file throws naming the path.
JointLog ReadJointLogCsv(const std::string& path, const RobotModel& model);

// The whole content of a text file. Throws std::invalid_argument
// "path: cannot read the file" when it is missing, a directory or unreadable.
std::string ReadTextFile(const std::string& path);

}  // namespace idbench
