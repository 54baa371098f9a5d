#include "log_columns.h"

#include <algorithm>
#include <stdexcept>

#include "header_columns.h"

namespace idbench::internal {

void FailAt(const std::string& source, std::int64_t line, const std::string& what) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
}

void ColumnMessages::Fail(const std::string& what) const {
  if (named) throw std::invalid_argument(ListName() + ": " + what);
  FailAt(source, header_line, what);
}

// The name of each file column: the header's (q.<joint name> read as that
// joint's number), the columns list's, or both reconciled. A header-less file
// needs a columns list; a header naming joints the robot does not have, or
// fewer than it has, is another robot's log.
std::vector<std::string> FileColumnNames(const std::vector<std::string>& first_fields, bool header,
                                         const RobotModel& model, const JointLogFormat& format,
                                         const ColumnMessages& messages, std::int64_t line_number,
                                         std::vector<std::string>* notes) {
  const std::string& source = messages.source;
  const int n_dof = model.n_dof();
  const bool named = !format.columns.empty();
  if (!named && !header) {
    const std::string example = "t,q1..q" + std::to_string(n_dof) + ",qd1..qd" + std::to_string(n_dof) + ",i1..i" +
                                std::to_string(n_dof);
    FailAt(source, line_number,
           "the first line is data (all numbers), not a header naming the columns: " +
               (messages.list.empty()
                    ? "pass `columns` with the names in file order, e.g. `columns` " + example
                    : "give " + messages.list + " with the names in file order, e.g. \"" + example + "\"") +
               " (_ skips a column)");
  }
  std::vector<std::string> header_names;  // idbench names; "" where the header uses others
  if (header) {
    for (size_t c = 0; c < first_fields.size(); ++c) {
      header_names.push_back(
          IdbenchColumnName(first_fields[c], c, model, source + ":" + std::to_string(line_number) + ": "));
      // A header naming joints the robot does not have is another robot's log,
      // whatever the columns list says.
      ColumnTarget target{};
      if (!header_names[c].empty() && ParseColumnName(header_names[c], &target) && target.kind > 0 &&
          target.joint >= n_dof) {
        FailAt(source, line_number,
               ColumnLabel(c, first_fields[c]) + ": the header names joint " + std::to_string(target.joint + 1) +
                   " but " + model.name() + " has " + std::to_string(n_dof) + " joints: is this a log of another robot?");
      }
    }
  }
  // And a header naming fewer joints than the robot has (q1..q5 for 6).
  if (header) {
    int most = 0;
    for (const std::string& name : header_names) {
      ColumnTarget target{};
      if (!name.empty() && ParseColumnName(name, &target) && target.kind > 0) most = std::max(most, target.joint + 1);
    }
    if (most > 0 && most < n_dof) {
      FailAt(source, line_number,
             "missing column 'q" + std::to_string(most + 1) + "' (robot has " + std::to_string(n_dof) +
                 " joints): the header names joints 1 to " + std::to_string(most) + " only: is this a log "
                 "of another robot?");
    }
  }
  std::vector<std::string> names;
  if (!named) {
    for (size_t c = 0; c < first_fields.size(); ++c) {
      names.push_back(header_names[c].empty() ? first_fields[c] : header_names[c]);
    }
  } else if (!header) {
    names = ExpandColumnNames(format.columns);
  } else {
    names = ReconcileColumnsWithHeader(ExpandColumnNames(format.columns), format.columns, first_fields, header_names,
                                       source, static_cast<int>(line_number), notes);
  }
  return names;
}

// Every column named once, from a known set, of a joint the robot has.
FileColumns TargetsOf(std::vector<std::string> names, int n_dof, const ColumnMessages& messages,
                      bool with_transmission) {
  if (static_cast<int>(names.size()) > JointLogFormat::kMaxColumns) {
    messages.Fail(std::to_string(names.size()) + " columns, at most " + std::to_string(JointLogFormat::kMaxColumns));
  }
  FileColumns columns;
  for (size_t c = 0; c < names.size(); ++c) {
    const std::string& name = names[c];
    const std::string where = ColumnLabel(c, name);
    ColumnTarget target{};
    if (const char* what = ActuatorColumn(name)) {
      if (!with_transmission) {
        messages.Fail(where + ": " + what + " (an actuator-side column): reading it needs the transmission (gear "
                      "ratios, coupling) from motor to joint: give \"transmission\" in a log description (or the "
                      "URDF's <transmission>), or joint-side columns (q, qd, qdd, tau, i)");
      }
      ParseActuatorColumnName(name, &target);
      if (target.joint >= n_dof) {
        messages.Fail(where + ": actuator " + std::to_string(target.joint + 1) + " but the robot has " +
                      std::to_string(n_dof) + " joints (one actuator each)");
      }
      const std::string joint_name = std::string(kKindPrefix[target.kind]) + std::to_string(target.joint + 1);
      if (!columns.column_of.emplace(joint_name, static_cast<int>(c)).second) {
        messages.Fail(where + ": " + what + " " + std::to_string(target.joint + 1) + " given twice, or with '" +
                      joint_name + "': give each kind of column on one side, actuator or joint");
      }
      columns.actuator_kinds |= 1u << target.kind;
      columns.targets.push_back(target);
      continue;
    }
    if (!ParseColumnName(name, &target)) {
      messages.Fail(where + ": unknown column; expected t, q1..q" + std::to_string(n_dof) +
                    ", qd*, qdd*, tau*, i* (motor current)" + (messages.named ? ", or _" : ""));
    }
    if (name != "_" && !columns.column_of.emplace(name, static_cast<int>(c)).second) {
      messages.Fail(where + ": repeated" + (with_transmission ? " (or given on the actuator side too)" : ""));
    }
    if (target.kind > 0) columns.joint_kinds |= 1u << target.kind;
    if (target.kind > 0 && target.joint >= n_dof) {
      messages.Fail(where + ": joint " + std::to_string(target.joint + 1) + " but the robot has " +
                    std::to_string(n_dof) + " joints");
    }
    columns.targets.push_back(target);
  }
  columns.names = std::move(names);
  return columns;
}

namespace {

// Whether all of prefix1..prefix<n_dof> are columns; none is false, some is
// an error.
bool CompleteSet(const FileColumns& columns, const char* prefix, int n_dof, const ColumnMessages& messages) {
  const std::string p(prefix);
  int count = 0;
  for (int j = 1; j <= n_dof; ++j) count += columns.has(p + std::to_string(j));
  if (count == 0 || count == n_dof) return count == n_dof;
  for (int j = 1; j <= n_dof; ++j) {
    if (!columns.has(p + std::to_string(j))) {
      if (columns.has(p + "1")) {
        messages.Fail("missing column '" + p + std::to_string(j) + "': give all of " + p + "1.." + p +
                      std::to_string(n_dof) + " or none");
      }
      break;
    }
  }
  for (int j = 2; j <= n_dof; ++j) {
    if (columns.has(p + std::to_string(j))) {
      messages.Fail("column '" + p + std::to_string(j) + "' without " + p + "1: give all of " + p + "1.." + p +
                    std::to_string(n_dof) + " or none");
    }
  }
  return false;
}

}  // namespace

// Required columns, each other kind as a complete set or not at all, and
// which torque columns fill log.tau as `torques` asks.
ColumnUse ChooseColumns(const FileColumns& columns, int n_dof, const JointLogFormat& format, TorqueColumns torques,
                        const ColumnMessages& messages, std::vector<std::string>* warnings, bool need_t) {
  if (need_t && !columns.has("t")) messages.Fail("missing column 't'");
  for (int kind = 1; kind < kKinds; ++kind) {
    const unsigned bit = 1u << kind;
    if ((columns.joint_kinds & bit) && (columns.actuator_kinds & bit)) {
      messages.Fail(std::string("columns ") + kKindPrefix[kind] + "* on the joint side and on the actuator side: give "
                    "each kind on one side");
    }
  }
  if ((columns.actuator_kinds & (1u << 5)) && torques == TorqueColumns::kCurrents) {
    messages.Fail("motor currents im*: drive gains are estimated from joint-side currents i*");
  }
  for (int j = 1; j <= n_dof; ++j) {
    if (!columns.has("q" + std::to_string(j))) {
      messages.Fail("missing column 'q" + std::to_string(j) + "' (robot has " + std::to_string(n_dof) + " joints)");
    }
  }
  ColumnUse use;
  use.has_qd = CompleteSet(columns, "qd", n_dof, messages);
  use.has_qdd = CompleteSet(columns, "qdd", n_dof, messages);
  const bool has_tau = CompleteSet(columns, "tau", n_dof, messages), has_i = CompleteSet(columns, "i", n_dof, messages);
  const std::string n_str = std::to_string(n_dof);
  use.use_tau = has_tau;
  switch (torques) {
    case TorqueColumns::kRequired:
      if (!format.drive_gains.empty()) {
        if (!has_i) messages.Fail("drive_gains given but the log has no motor currents i1..i" + n_str);
        use.use_i = true;
        use.use_tau = false;
        if (has_tau) {
          warnings->push_back(messages.source + ": tau columns ignored: drive_gains given, tau = K·i from i1..i" +
                              n_str);
        }
      } else if (!has_tau) {
        if (has_i) {
          messages.Fail("the log has motor currents i1..i" + n_str + " but no tau: pass drive_gains K1,...,K" +
                        n_str + " (tau = K·i; `idbench gains` estimates them)");
        }
        messages.Fail("missing column 'tau1' (robot has " + n_str + " joints)");
      }
      break;
    case TorqueColumns::kOptional:
      break;
    case TorqueColumns::kCurrents:
      if (!has_i) messages.Fail("missing column 'i1': drive gains need the motor currents i1..i" + n_str);
      use.use_i = true;
      use.use_tau = false;
      break;
  }
  return use;
}

}  // namespace idbench::internal
