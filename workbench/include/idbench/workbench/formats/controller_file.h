// A joint controller file (simulate's and identify's `controller`):
//   {"kp": [...], "kd": [...], "ki": [...], "tau_max": [...], "feedforward": "model"}
// each gain one number for every joint or an array of one per joint; kp and
// kd required, ki and tau_max optional (0, no limit), feedforward "model"
// (the robot file's inverse dynamics along the reference) or "none".
#pragma once

#include <string>

#include "idbench/engine/joint_controller.h"

namespace idbench {

// Parses `text` read from `source`; checks the gains against n_dof joints.
// Throws std::invalid_argument starting with "source: " and naming the key
// (".kp[2]: expected a finite number, got \"x\"", "kd: expected one value or
// 6 (one per joint), got 2").
JointControllerOptions ParseControllerJson(const std::string& text, const std::string& source, int n_dof);

// The same from the file at `path` (input_file.h: missing, too large, a directory).
JointControllerOptions ReadControllerFile(const std::string& path, int n_dof);

}  // namespace idbench
