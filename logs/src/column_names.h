// Joint-log column names (README.md, "Joint logs"): t, q<j>, qd<j>, qdd<j>,
// tau<j>, i<j>, qr<j> and "_", where each column's values go, and how a column is
// named in messages.
#pragma once

#include <cstddef>
#include <string>

#include "idbench/engine/robot_model.h"

namespace idbench::internal {

// Where a column's values go: kind (0 t, 1 q, 2 qd, 3 qdd, 4 tau, 5 i;
// -1 skipped) and joint.
struct ColumnTarget {
  int kind;
  int joint;              // the joint, or the actuator when `actuator`
  bool actuator = false;  // an actuator-side column (qm, qdm, taum, im: kinds 1, 2, 4, 5)
};
constexpr const char* kKindPrefix[] = {"t", "q", "qd", "qdd", "tau", "i"};
constexpr int kKinds = 6;
constexpr const char* kReferencePrefix = "qr";

// Parses a column name: t, q<j>, qd<j>, qdd<j>, tau<j>, i<j> (j >= 1), "_",
// or qr<j> (a closed loop's reference position, skipped as "_" is: kind −1).
// Returns false for anything else.
bool ParseColumnName(const std::string& name, ColumnTarget* target);

// For an actuator-side column name (qm<j> motor position, qdm<j> motor
// velocity, taum<j> motor torque, im<j> motor current), what it is ("motor
// position"); nullptr for any other name.
const char* ActuatorColumn(const std::string& name);
// An actuator-side name as its target: qm<k> → {1, k − 1, true}, qdm → 2,
// taum → 4, im → 5. False for any other name.
bool ParseActuatorColumnName(const std::string& name, ColumnTarget* target);
// Its prefix's kind for ranges (qm1..qm6): 0..3 in kActuatorPrefix, or -1.
int ActuatorPrefix(const std::string& prefix);
constexpr const char* kActuatorPrefix[] = {"qm", "qdm", "taum", "im"};

// "column C ('name')" for messages, C counted from 1, the name escaped and cut.
std::string ColumnLabel(size_t c, const std::string& name);

// A header field as an idbench column name: itself when it is one (t, q3,
// tau1, ...); q.<joint name>, qd.<..>, qdd.<..>, tau.<..>, i.<..> (as
// trajectory.csv is headed) → the joint's number; "" for any other name (a
// vendor's, e.g. Joint_1). A joint name the robot does not have throws.
std::string IdbenchColumnName(const std::string& field, size_t c, const RobotModel& model, const std::string& where);

}  // namespace idbench::internal
