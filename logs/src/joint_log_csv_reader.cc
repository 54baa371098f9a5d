#include "idbench/logs/joint_log_csv_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string_view>
#include <stdexcept>
#include <vector>

#include "angle_unit_check.h"
#include "column_names.h"
#include "csv_fields.h"
#include "header_columns.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/printable_text.h"
#include "number_format.h"

namespace idbench {

using internal::AllNumbers;
using internal::ColumnLabel;
using internal::ColumnTarget;
using internal::IdbenchColumnName;
using internal::ParseColumnName;
using internal::ReconcileColumnsWithHeader;
using internal::SplitFields;
using internal::WarnIfRadiansReadAsDegrees;

namespace {

// A UTF-8 byte order mark (spreadsheets write one) is not part of the first
// column's name.
constexpr std::string_view kBom = "\xef\xbb\xbf";

// "source:line: what".
[[noreturn]] void FailAt(const std::string& source, int line, const std::string& what) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
}

// Where a problem with the columns is reported: the columns list when it
// names them, else the header line.
struct ColumnMessages {
  const std::string& source;
  bool named;       // the format's columns list names the columns
  int header_line;  // 0 when named

  [[noreturn]] void Fail(const std::string& what) const {
    if (named) throw std::invalid_argument(source + ": --columns: " + what);
    FailAt(source, header_line, what);
  }
};

// The file's columns: the name of each, where its values go, and the column
// of each name used.
struct FileColumns {
  std::vector<std::string> names;
  std::vector<ColumnTarget> targets;
  std::map<std::string, int> column_of;
  bool has(const std::string& name) const { return column_of.count(name) > 0; }
};

// Which of the optional columns the log fills.
struct ColumnUse {
  bool has_qd = false, has_qdd = false;
  bool use_tau = false;  // log.tau from the tau columns
  bool use_i = false;    // log.tau from the i columns (K·i, or the currents for kCurrents)
};

// The first non-blank line (the header, or data when the columns list names
// them) split into fields; *line_number is its line.
std::vector<std::string> FirstLineFields(std::istream& in, const JointLogFormat& format, const std::string& source,
                                         int* line_number) {
  std::string line;
  while (std::getline(in, line)) {
    ++*line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  if (*line_number == 0 || line.find_first_not_of(" \t\r") == std::string::npos) {
    FailAt(source, std::max(*line_number, 1),
           format.columns.empty() ? "empty file, expected a header line" : "empty file");
  }
  return SplitFields(line);
}

// The name of each file column: the header's (q.<joint name> read as that
// joint's number), the columns list's, or both reconciled. A header-less file
// needs a columns list; a header naming joints the robot does not have, or
// fewer than it has, is another robot's log.
std::vector<std::string> FileColumnNames(const std::vector<std::string>& first_fields, bool header,
                                         const RobotModel& model, const JointLogFormat& format,
                                         const std::string& source, int line_number, std::vector<std::string>* notes) {
  const int n_dof = model.n_dof();
  const bool named = !format.columns.empty();
  if (!named && !header) {
    FailAt(source, line_number,
           "the first line is data (all numbers), not a header naming the columns: pass --columns with "
           "the names in file order, e.g. --columns t,q1..q" + std::to_string(n_dof) + ",qd1..qd" +
               std::to_string(n_dof) + ",i1..i" + std::to_string(n_dof) + " (_ skips a column)");
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
                                       source, line_number, notes);
  }
  return names;
}

// Every column named once, from a known set, of a joint the robot has.
FileColumns TargetsOf(std::vector<std::string> names, int n_dof, const ColumnMessages& messages) {
  if (static_cast<int>(names.size()) > JointLogFormat::kMaxColumns) {
    messages.Fail(std::to_string(names.size()) + " columns, at most " + std::to_string(JointLogFormat::kMaxColumns));
  }
  FileColumns columns;
  for (size_t c = 0; c < names.size(); ++c) {
    const std::string& name = names[c];
    const std::string where = ColumnLabel(c, name);
    ColumnTarget target{};
    if (!ParseColumnName(name, &target)) {
      messages.Fail(where + ": unknown column; expected t, q1..q" + std::to_string(n_dof) +
                    ", qd*, qdd*, tau*, i* (motor current)" + (messages.named ? ", or _" : ""));
    }
    if (name != "_" && !columns.column_of.emplace(name, static_cast<int>(c)).second) messages.Fail(where + ": repeated");
    if (target.kind > 0 && target.joint >= n_dof) {
      messages.Fail(where + ": joint " + std::to_string(target.joint + 1) + " but the robot has " +
                    std::to_string(n_dof) + " joints");
    }
    columns.targets.push_back(target);
  }
  columns.names = std::move(names);
  return columns;
}

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

// Required columns, each other kind as a complete set or not at all, and
// which torque columns fill log.tau as `torques` asks.
ColumnUse ChooseColumns(const FileColumns& columns, int n_dof, const JointLogFormat& format, TorqueColumns torques,
                        const ColumnMessages& messages, std::vector<std::string>* warnings) {
  if (!columns.has("t")) messages.Fail("missing column 't'");
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
        if (!has_i) messages.Fail("--drive-gains given but the log has no motor currents i1..i" + n_str);
        use.use_i = true;
        use.use_tau = false;
        if (has_tau) {
          warnings->push_back(messages.source + ": tau columns ignored: --drive-gains given, tau = K·i from i1..i" +
                              n_str);
        }
      } else if (!has_tau) {
        if (has_i) {
          messages.Fail("the log has motor currents i1..i" + n_str + " but no tau: pass --drive-gains K1,...,K" +
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

// The data lines as numbers, one row per sample (angles in rad), with their
// file lines: every used field a finite number, positions within the joint
// limits, time strictly increasing. With a columns list, fields after the
// named ones are ignored; `in` stands after the first line.
std::vector<std::vector<double>> ReadDataRows(std::istringstream& in, const std::string& text,
                                              const FileColumns& columns, const RobotModel& model,
                                              const JointLogFormat& format, const std::string& source, bool header,
                                              int line_number, std::vector<int>* lines) {
  const bool named = !format.columns.empty();
  const std::vector<std::string>& names = columns.names;
  const std::vector<ColumnTarget>& targets = columns.targets;
  const bool degrees = format.degrees();
  const double to_rad = degrees ? std::numbers::pi / 180.0 : 1.0;
  std::vector<std::vector<double>> rows;
  const size_t t_column = static_cast<size_t>(columns.column_of.at("t"));
  if (named && header) {
    // The first line is a header that --columns overrides: skipped.
  } else if (named) {
    in.clear();
    in.str(text.starts_with(kBom) ? text.substr(kBom.size()) : text);  // the first line is data: read it again
    line_number = 0;
  }
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = SplitFields(line);
    if (named ? fields.size() < names.size() : fields.size() != names.size()) {
      FailAt(source, line_number,
             std::to_string(fields.size()) + " fields, expected " + (named ? "at least " : "") +
                 std::to_string(names.size()));
    }
    std::vector<double> values(names.size(), 0.0);
    for (size_t c = 0; c < names.size(); ++c) {
      if (targets[c].kind < 0) continue;
      const std::string& f = fields[c];
      const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), values[c]);
      const std::string where = ColumnLabel(c, names[c]);
      if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) {
        FailAt(source, line_number, where + ": '" + PrintableText(f) + "' is not a number");
      }
      if (!std::isfinite(values[c])) FailAt(source, line_number, where + ": " + f + " is not finite");
      if (targets[c].kind >= 1 && targets[c].kind <= 3) values[c] *= to_rad;
      if (targets[c].kind == 1) {
        const JointLimits& limits = model.link(targets[c].joint).limits;
        if (values[c] < limits.q_min || values[c] > limits.q_max) {
          FailAt(source, line_number,
                 where + ": " + f + (degrees ? " deg (" + Shortest(values[c]) + " rad)" : " rad") +
                     " is outside joint " + std::to_string(targets[c].joint + 1) + "'s limits [" +
                     std::to_string(limits.q_min) + ", " + std::to_string(limits.q_max) + "] rad");
        }
      }
    }
    const double t = values[t_column];
    if (!rows.empty() && !(t > rows.back()[t_column])) {
      FailAt(source, line_number,
             "column " + std::to_string(t_column + 1) + " ('t'): time " + std::to_string(t) + " does not increase");
    }
    rows.push_back(std::move(values));
    lines->push_back(line_number);
  }
  if (rows.empty()) FailAt(source, line_number, named && !header ? "no data lines" : "no data lines after the header");
  return rows;
}

// Columns into the log's matrices; currents × gains into tau (kRequired).
void FillLog(const std::vector<std::vector<double>>& rows, const FileColumns& columns, const ColumnUse& use,
             int n_dof, const JointLogFormat& format, TorqueColumns torques, RecordedJointLog* out) {
  const int n_samples = static_cast<int>(rows.size());
  JointLog& log = out->log;
  log.t.resize(n_samples);
  log.q.resize(n_samples, n_dof);
  if (use.has_qd) log.qd.resize(n_samples, n_dof);
  if (use.has_qdd) log.qdd.resize(n_samples, n_dof);
  if (use.use_tau || use.use_i) log.tau.resize(n_samples, n_dof);
  Eigen::MatrixXd* matrices[] = {nullptr, &log.q, &log.qd, &log.qdd, use.use_tau ? &log.tau : nullptr,
                                 use.use_i ? &log.tau : nullptr};
  const bool scale = use.use_i && torques == TorqueColumns::kRequired;
  out->torque_from_currents = scale;
  for (int s = 0; s < n_samples; ++s) {
    for (size_t c = 0; c < columns.targets.size(); ++c) {
      const double v = rows[static_cast<size_t>(s)][c];
      const ColumnTarget& target = columns.targets[c];
      if (target.kind == 0) {
        log.t[s] = v;
      } else if (target.kind > 0 && matrices[target.kind]) {
        (*matrices[target.kind])(s, target.joint) =
            target.kind == 5 && scale ? format.drive_gains[static_cast<size_t>(target.joint)] * v : v;
      }
    }
  }
}

}  // namespace

RecordedJointLog ParseRecordedJointLog(const std::string& text, const RobotModel& model, const std::string& source,
                                       const JointLogFormat& format, TorqueColumns torques) {
  const int n_dof = model.n_dof();
  std::string why;
  if (!format.IsValid(&why) || !format.IsValidFor(n_dof, &why)) throw std::invalid_argument(why);
  std::istringstream in(text.starts_with(kBom) ? text.substr(kBom.size()) : text);
  CheckLineLengths(text, source);

  // The first line: a header, or data when the columns list names the columns.
  int line_number = 0;
  const std::vector<std::string> first_fields = FirstLineFields(in, format, source, &line_number);
  const bool header = !AllNumbers(first_fields);
  const bool named = !format.columns.empty();

  // The columns: their names, where each goes, which ones fill the log.
  RecordedJointLog out;
  const ColumnMessages messages{source, named, named ? 0 : line_number};
  const FileColumns columns =
      TargetsOf(FileColumnNames(first_fields, header, model, format, source, line_number, &out.notes), n_dof, messages);
  const ColumnUse use = ChooseColumns(columns, n_dof, format, torques, messages, &out.warnings);

  // The data lines, then their values into the log.
  const std::vector<std::vector<double>> rows =
      ReadDataRows(in, text, columns, model, format, source, header, line_number, &out.lines);
  FillLog(rows, columns, use, n_dof, format, torques, &out);
  WarnIfRadiansReadAsDegrees(format, source, out.log.q, &out.warnings);
  return out;
}

RecordedJointLog ReadRecordedJointLog(const std::string& path, const RobotModel& model, const JointLogFormat& format,
                                      TorqueColumns torques) {
  return ParseRecordedJointLog(ReadInputFile(path), model, path, format, torques);
}

JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source,
                          TorqueColumns torques) {
  RecordedJointLog recorded = ParseRecordedJointLog(text, model, source, JointLogFormat{}, torques);
  JointLog& log = recorded.log;
  if ((log.qd.size() > 0) != (log.qdd.size() > 0)) {
    throw std::invalid_argument(source + ":" + std::to_string(recorded.lines.front() - 1) + ": column '" +
                                (log.qd.size() > 0 ? "qd1' without qdd1" : "qdd1' without qd1") +
                                ": a trajectory needs qd and qdd both or neither");
  }
  if (torques == TorqueColumns::kCurrents) log.tau.resize(0, 0);
  return std::move(log);
}

}  // namespace idbench
