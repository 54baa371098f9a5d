// A joint log as recorded, before any resampling or filtering: read from a
// CSV file (joint_log_csv_reader.h) or from arrays.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"

namespace idbench {

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

}  // namespace idbench
