// How a joint log's columns are read (README.md, "Joint logs"): the column
// names, the angle unit, the drive gains, and what the torque columns must be.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/transmission.h"

namespace idbench {

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
  // For a rosbag2 bag: the sensor_msgs/msg/JointState topic to read;
  // empty: the bag's only one.
  std::string topic;
  // Actuator to joint (transmission.h): with it, actuator-side columns qm<k>
  // (motor position), qdm<k>, taum<k> and im<k> (motor current, × drive
  // gain k) are read and mapped to the joint side (q = A⁻¹·θm + q0,
  // q̇ = A⁻¹·θ̇m, τ = Aᵀ·τm). A log description's own wins (a note says so).
  std::optional<Transmission> transmission;
  // The torques (or currents) are commands held from their sample to the
  // next (zero-order hold, as a controller applies them): each is read as the
  // mean of its hold and the previous one's, the torque the motion saw around
  // its sample (held_torque_source.h).
  bool torque_held = false;

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
// std::invalid_argument "columns: ..." for a malformed range or more than
// kMaxColumns names.
std::vector<std::string> ExpandColumnNames(const std::vector<std::string>& items);

// What the torque columns must be: a joint log for identification (tau, or
// currents i with drive gains), a trajectory (tau optional, currents
// ignored), or a log for drive-gain estimation (currents i required; tau
// ignored).
enum class TorqueColumns { kRequired, kOptional, kCurrents };

}  // namespace idbench
