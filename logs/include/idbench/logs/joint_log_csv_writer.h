// Writes a joint log in the joint-log CSV format (joint_log_csv_reader.h):
// a header naming the columns, then one sample per line, numbers in their
// shortest round-trip form.
#pragma once

#include <string>

#include "idbench/engine/measurements.h"

namespace idbench {

// Writes the columns the log has: t, q, qd and qdd if present, tau if present,
// then, given a closed loop's reference positions q_ref (n_samples × n_dof
// [rad]), qr1..qrn (which the readers skip). Throws std::invalid_argument
// when q_ref has another shape.
std::string FormatJointLogCsv(const JointLog& log, const Eigen::MatrixXd* q_ref = nullptr);

}  // namespace idbench
