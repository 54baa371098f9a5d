// The joint-log CSV format (README.md, "Joint logs"): a header naming the
// columns (or names from --columns), then one sample per line:
//   t, q1..qn, [qd1..qdn,] [qdd1..qddn,] tau1..taun | i1..in
// Columns may come in any order; qd and qdd are each optional.
// A trajectory file (trajectory_file.h) is the same format with tau optional.
// Numbers are written in their shortest round-trip form.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"

namespace idbench {

// Writes the columns the log has: t, q, qd and qdd if present, tau if present.
std::string FormatJointLogCsv(const JointLog& log);

// How a log file's columns are read (README.md, "Joint logs"): what the CLI's
// --columns, --angle-unit and --drive-gains fill.
struct JointLogFormat {
  // Column names in file order. Items: t, q<j>, qd<j>, qdd<j>, tau<j>, i<j>
  // (motor current), ranges such as "q1..q6", and "_" for a column to skip;
  // fields after the named ones are ignored. Empty: the file's header line
  // names the columns (idbench's names, or q.<joint name> etc.). Over a
  // header (README "Joint logs"): where the header uses idbench's names the
  // list must agree with it column by column, or name fewer columns that all
  // appear in it (then matched by name, with a note); other header names are
  // renamed in order (a note prints the mapping); anything else is an error
  // naming both.
  std::vector<std::string> columns;
  std::string angle_unit = "rad";    // of q, qd, qdd in the file: "rad" or "deg"
  // Drive gains [N m/A], one per joint: τ = K·i from the i columns. When
  // given, they are used even if the file also has tau columns (a warning
  // says so): the option is explicit, a column may be the controller's own
  // target torque.
  std::vector<double> drive_gains;

  static constexpr int kMaxColumns = 1024;  // named columns, ranges expanded
  // Bounds on |K| [N m/A]: a joint-side gain (motor constant × gear ratio)
  // lies far inside them; 1e-300 or 1e300 is a typing error.
  static constexpr double kMinDriveGain = 1e-6, kMaxDriveGain = 1e6;
  static constexpr int kMaxJoints = 64;

  bool degrees() const { return angle_unit == "deg"; }
  // Checks the options alone (syntax of the names, unit, gains of magnitude
  // kMinDriveGain..kMaxDriveGain, not all negative); *why names the option.
  bool IsValid(std::string* why) const;
  // And against a robot: joints named in --columns and gains per joint.
  bool IsValidFor(int n_dof, std::string* why) const;
};

// The --columns items with ranges expanded ("q1..q3" → q1, q2, q3). Throws
// std::invalid_argument "--columns: ..." for a malformed range or more than
// kMaxColumns names.
std::vector<std::string> ExpandColumnNames(const std::vector<std::string>& items);

// What the torque columns must be: a joint log for identification (tau, or
// currents i with drive gains), a trajectory (tau optional, currents
// ignored), or a log for drive-gain estimation (currents i required; tau
// ignored).
enum class TorqueColumns { kRequired, kOptional, kCurrents };

// A log as read from a file, before any resampling or filtering.
struct RecordedJointLog {
  // t, q, and each of qd, qdd, tau as recorded (each may be empty, 0 × 0);
  // angles in rad. kRequired: tau [N m] from the tau columns or K·i;
  // kCurrents: tau holds the motor currents [A].
  JointLog log;
  std::vector<int> lines;             // file line of each sample (n_samples)
  std::vector<std::string> warnings;  // e.g. tau columns ignored for K·i
  std::vector<std::string> notes;     // how the columns were mapped (a columns list over a header)
  bool torque_from_currents = false;  // tau = K·i
};

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
// A log given as arrays (e.g. a Python dict) keyed t, q, qd, qdd, tau, i,
// read as a file would be in `format` (columns must be empty): angles in
// format.angle_unit converted to rad and checked against the joint limits,
// tau = K·i when drive_gains are given, what `torques` needs present. Each
// joint array has one row per sample of t and one column per joint. Throws
// std::invalid_argument "source: key: what" naming the array at fault. lines
// are row numbers (from 0).
RecordedJointLog RecordedJointLogFromArrays(const std::map<std::string, Eigen::MatrixXd>& arrays,
                                            const RobotModel& model, const std::string& source,
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
