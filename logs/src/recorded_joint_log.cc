#include "idbench/logs/recorded_joint_log.h"

#include <numbers>
#include <stdexcept>

#include "angle_unit_check.h"
#include "idbench/engine/printable_text.h"
#include "number_format.h"

namespace idbench {

using internal::WarnIfRadiansReadAsDegrees;

RecordedJointLog RecordedJointLogFromArrays(const std::map<std::string, Eigen::MatrixXd>& arrays,
                                            const RobotModel& model, const std::string& source,
                                            const JointLogFormat& format, TorqueColumns torques) {
  const int n_dof = model.n_dof();
  auto fail = [&](const std::string& what) -> void { throw std::invalid_argument(source + ": " + what); };
  std::string why;
  if (!format.IsValid(&why) || !format.IsValidFor(n_dof, &why)) throw std::invalid_argument(why);
  if (!format.columns.empty()) fail("columns: applies to CSV files; the arrays are named by their keys");
  for (const auto& [key, value] : arrays) {
    if (key != "t" && key != "q" && key != "qd" && key != "qdd" && key != "tau" && key != "i") {
      fail("unknown array '" + PrintableText(key) + "'; expected t, q, qd, qdd, tau, i (motor currents)");
    }
  }
  auto find = [&](const char* key) -> const Eigen::MatrixXd* {
    const auto it = arrays.find(key);
    return it == arrays.end() ? nullptr : &it->second;
  };
  RecordedJointLog out;
  JointLog& log = out.log;
  // t: one time per sample, strictly increasing.
  const Eigen::MatrixXd* t = find("t");
  if (!t) fail("missing the array 't' (sample times [s])");
  if (t->cols() != 1 && t->rows() != 1) fail("t: expected a 1-D array of sample times [s]");
  log.t = Eigen::Map<const Eigen::VectorXd>(t->data(), t->size());
  if (log.t.size() == 0) fail("t: no samples");
  if (!log.t.allFinite()) fail("t: not every value is a finite number");
  for (Eigen::Index k = 1; k < log.t.size(); ++k) {
    if (!(log.t[k] > log.t[k - 1])) fail("t: not strictly increasing at sample " + std::to_string(k));
  }
  // The joint arrays: one row per sample of t, one column per joint.
  const Eigen::Index n = log.t.size();
  auto take = [&](const char* key, Eigen::MatrixXd* x) {
    const Eigen::MatrixXd* a = find(key);
    if (!a) return false;
    if (a->rows() != n) {
      fail(std::string(key) + ": " + std::to_string(a->rows()) + " rows but t has " + std::to_string(n) +
           " samples: every array needs one row per sample of t");
    }
    if (a->cols() != n_dof) {
      fail(std::string(key) + ": " + std::to_string(a->cols()) + " columns but " + model.name() + " has " +
           std::to_string(n_dof) + " joints");
    }
    if (!a->allFinite()) fail(std::string(key) + ": not every value is a finite number");
    *x = *a;
    return true;
  };
  if (!take("q", &log.q)) fail("missing the array 'q' (joint positions)");
  take("qd", &log.qd);
  take("qdd", &log.qdd);
  // Angles in the format's unit, positions within the joint limits.
  if (format.degrees()) {
    for (Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd}) *x *= std::numbers::pi / 180.0;
  }
  for (Eigen::Index s = 0; s < n; ++s) {
    for (int j = 0; j < n_dof; ++j) {
      const JointLimits& limits = model.link(j).limits;
      if (log.q(s, j) < limits.q_min || log.q(s, j) > limits.q_max) {
        fail("q: row " + std::to_string(s) + ", joint " + std::to_string(j + 1) + ": " + Shortest(log.q(s, j)) +
             " rad is outside the joint's limits [" + Shortest(limits.q_min) + ", " + Shortest(limits.q_max) + "] rad" +
             (format.degrees() ? " (read with angle_unit deg)" : ""));
      }
    }
  }
  // Torques: tau, or K·i with drive gains, as for a file.
  Eigen::MatrixXd tau, current;
  const bool has_tau = take("tau", &tau), has_i = take("i", &current);
  switch (torques) {
    case TorqueColumns::kRequired:
      if (!format.drive_gains.empty()) {
        if (!has_i) fail("drive_gains given but there is no array 'i' (motor currents [A])");
        if (has_tau) out.warnings.push_back(source + ": array 'tau' ignored: drive_gains given, tau = K·i from 'i'");
        log.tau = current * Eigen::Map<const Eigen::VectorXd>(format.drive_gains.data(), n_dof).asDiagonal();
        out.torque_from_currents = true;
      } else if (has_tau) {
        log.tau = std::move(tau);
      } else {
        fail(has_i ? "there are motor currents 'i' but no 'tau': give drive_gains (tau = K·i)"
                   : "missing the array 'tau' (joint torques [N m])");
      }
      break;
    case TorqueColumns::kOptional:
      if (has_tau) log.tau = std::move(tau);
      break;
    case TorqueColumns::kCurrents:
      if (!has_i) fail("missing the array 'i' (motor currents [A])");
      log.tau = std::move(current);
      break;
  }
  out.lines.resize(static_cast<size_t>(n));
  for (size_t k = 0; k < out.lines.size(); ++k) out.lines[k] = static_cast<int>(k);  // row numbers
  WarnIfRadiansReadAsDegrees(format, source, out.log.q, &out.warnings);
  return out;
}

}  // namespace idbench
