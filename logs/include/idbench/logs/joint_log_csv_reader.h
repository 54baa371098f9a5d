// The joint-log CSV format (README.md, "Joint logs"): a header naming the
// columns (or names from --columns), then one sample per line:
//   t, q1..qn, [qd1..qdn,] [qdd1..qddn,] tau1..taun | i1..in
// Columns may come in any order; qd and qdd are each optional.
// A trajectory file (trajectory_file.h) is the same format with tau optional.
#pragma once

#include <memory>
#include <string>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"
#include "idbench/logs/recorded_joint_log.h"

namespace idbench {

// Parses a log of `model`. `source` names the file in messages. A header
// naming a joint the robot does not have (q7 on a 6-joint robot, an unknown
// q.<joint name>) is another robot's log: an error. With angle_unit deg, a
// log in which no joint moves more than 5° draws a warning (radians read as
// degrees). Throws
// std::invalid_argument with "source:line: column c ('name'): what" for: a
// missing, unknown or repeated column (or one given in part: qd, qdd, tau, i
// are each all n or none), a joint the robot does not have, a header-less
// file without format.columns, a line with the wrong number of fields (fewer
// than named with --columns), a field that is not a finite number, time not
// strictly increasing, a position outside the joint's limits (after unit
// conversion), no data, currents without gains (kRequired), gains without
// currents.
RecordedJointLog ParseRecordedJointLog(const std::string& text, const RobotModel& model, const std::string& source,
                                       const JointLogFormat& format, TorqueColumns torques);
// The same file streamed: read in blocks (never whole), its header and
// columns checked when opened, each chunk's lines as they are handed out
// (Next throws the same messages). The degree warning is in layout().warnings
// after the last chunk. ParseRecordedJointLog and ReadRecordedJointLog are
// this source read whole.
std::unique_ptr<JointLogSource> OpenJointLogCsv(const std::string& path, const RobotModel& model,
                                                const JointLogFormat& format, TorqueColumns torques);
// Reads and parses a file; an unreadable file throws naming the path.
RecordedJointLog ReadRecordedJointLog(const std::string& path, const RobotModel& model, const JointLogFormat& format,
                                      TorqueColumns torques);

// A log in the default format (header, rad) as a trajectory or a simulated
// log reads it: qd and qdd both or neither (throws otherwise), tau as
// `torques` says (kRequired: tau columns; kOptional: log.tau empty when
// absent).
JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source,
                          TorqueColumns torques = TorqueColumns::kRequired);

}  // namespace idbench
