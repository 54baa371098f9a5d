#include "idbench/workbench/formats/joint_log_csv.h"

#include "number_format.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/printable_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

// "column C ('name')" for messages, C counted from 1, the name escaped and cut.
std::string ColumnLabel(size_t c, const std::string& name) {
  return "column " + std::to_string(c + 1) + " ('" + PrintableText(name) + "')";
}

// Splits one CSV line on commas (no quoting: every field is a name or a number).
std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.pop_back();
    const size_t first = field.find_first_not_of(" \t");
    fields.push_back(first == std::string::npos ? "" : field.substr(first));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

// Where a column's values go: kind (0 t, 1 q, 2 qd, 3 qdd, 4 tau, 5 i;
// -1 skipped) and joint.
struct ColumnTarget {
  int kind;
  int joint;
};
constexpr const char* kKindPrefix[] = {"t", "q", "qd", "qdd", "tau", "i"};
constexpr int kKinds = 6;

// Parses a column name: t, q<j>, qd<j>, qdd<j>, tau<j>, i<j> (j >= 1) or "_".
// Returns false for anything else.
bool ParseColumnName(const std::string& name, ColumnTarget* target) {
  if (name == "_") {
    *target = {-1, 0};
    return true;
  }
  if (name == "t") {
    *target = {0, 0};
    return true;
  }
  const size_t digits = name.find_first_of("0123456789");
  if (digits == std::string::npos || digits == 0) return false;
  const std::string prefix = name.substr(0, digits);
  int joint = 0;
  const char* end = name.data() + name.size();
  const auto [ptr, ec] = std::from_chars(name.data() + digits, end, joint);
  if (ec != std::errc() || ptr != end || joint < 1) return false;
  for (int kind = 1; kind < kKinds; ++kind) {
    if (prefix == kKindPrefix[kind]) {
      *target = {kind, joint - 1};
      return true;
    }
  }
  return false;
}

// Whether every field of a line is a number (a data line, not a header).
bool AllNumbers(const std::vector<std::string>& fields) {
  for (const std::string& f : fields) {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) return false;
  }
  return true;
}

// A header field as an idbench column name: itself when it is one (t, q3,
// tau1, ...); q.<joint name>, qd.<..>, qdd.<..>, tau.<..>, i.<..> (as
// trajectory.csv is headed) → the joint's number; "" for any other name (a
// vendor's, e.g. Joint_1). A joint name the robot does not have throws.
std::string IdbenchColumnName(const std::string& field, size_t c, const RobotModel& model, const std::string& where) {
  ColumnTarget target{};
  if (field != "_" && ParseColumnName(field, &target)) return field;
  const size_t dot = field.find('.');
  if (dot == std::string::npos) return "";
  const std::string prefix = field.substr(0, dot), joint = field.substr(dot + 1);
  bool known_prefix = false;
  for (int kind = 1; kind < kKinds; ++kind) known_prefix = known_prefix || prefix == kKindPrefix[kind];
  if (!known_prefix || joint.empty()) return "";
  for (int j = 0; j < model.n_dof(); ++j) {
    if (model.link(j).joint_name == joint) return prefix + std::to_string(j + 1);
  }
  std::string joints;
  for (int j = 0; j < model.n_dof(); ++j) joints += (j ? ", " : "") + model.link(j).joint_name;
  throw std::invalid_argument(where + ColumnLabel(c, field) + ": no joint '" + PrintableText(joint) + "' in " +
                              model.name() + " (its joints: " + joints + "): is this a log of another robot?");
}

// With angle_unit "deg", a log whose every joint moves less than
// kSmallMotionDeg is most likely in radians (a motion of 2 rad read as 2°):
// a warning, since a log of small motions in degrees is possible.
constexpr double kSmallMotionDeg = 5.0;
void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, RecordedJointLog* out) {
  const Eigen::MatrixXd& q = out->log.q;
  if (!format.degrees() || q.rows() < 2) return;
  const double span_deg = (q.colwise().maxCoeff() - q.colwise().minCoeff()).maxCoeff() * 180.0 / std::numbers::pi;
  if (span_deg < kSmallMotionDeg) {
    out->warnings.push_back(source + ": with angle_unit deg no joint moves more than " + Shortest(span_deg) +
                            "° over the log (less than " + Shortest(kSmallMotionDeg) +
                            "°): is the log in radians? Read in degrees, a motion of 2 rad becomes 2°, and the fit "
                            "is then badly conditioned");
  }
}

// The user's columns list as given (ranges unexpanded), for messages.
std::string JoinItems(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ",") + PrintableText(item);
  return out;
}

// A header and a columns list together (README "Joint logs"). `header` holds
// the header's fields as idbench names ("" where the header uses other
// names). The columns list must agree with the header wherever the header
// uses idbench names (or skip the column, "_"), and may rename the others in
// order; a list of fewer columns that all appear in the header takes them by
// name. Anything else contradicts the header: throws naming both. Returns
// the name of each file column ("_": not used); notes say how it was mapped.
std::vector<std::string> ReconcileColumnsWithHeader(const std::vector<std::string>& columns,
                                                    const std::vector<std::string>& items,
                                                    const std::vector<std::string>& raw_header,
                                                    const std::vector<std::string>& header, const std::string& source,
                                                    int line, std::vector<std::string>* notes) {
  const std::string where = source + ":" + std::to_string(line) + ": ";
  auto known = [&](size_t c) { return c < header.size() && !header[c].empty(); };
  if (columns.size() > raw_header.size()) {
    throw std::invalid_argument(where + "the columns list names " + std::to_string(columns.size()) +
                                " columns but the header has " + std::to_string(raw_header.size()));
  }
  // In file order: each named column agrees with an idbench header name, or renames another name.
  size_t conflict = columns.size();
  for (size_t c = 0; c < columns.size() && conflict == columns.size(); ++c) {
    if (columns[c] != "_" && known(c) && columns[c] != header[c]) conflict = c;
  }
  if (conflict == columns.size()) {
    std::string renamed;
    int n_renamed = 0;
    for (size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] == "_" || known(c)) continue;
      if (n_renamed++ < 24) renamed += (renamed.empty() ? "" : ", ") + ("'" + PrintableText(raw_header[c]) + "' → " + columns[c]);
    }
    if (n_renamed > 24) renamed += ", … (" + std::to_string(n_renamed) + " in all)";
    if (n_renamed > 0) notes->push_back(source + ": columns renames the header's columns in file order: " + renamed);
    return columns;
  }
  // A subset of the header's names, taken by name.
  std::map<std::string, size_t> header_column;
  for (size_t c = 0; c < header.size(); ++c) {
    if (known(c)) header_column.emplace(header[c], c);
  }
  std::string absent;
  bool skip = false;
  for (const std::string& name : columns) {
    skip = skip || name == "_";
    if (name != "_" && !header_column.count(name) && absent.empty()) absent = name;
  }
  if (absent.empty() && !skip && columns.size() < raw_header.size()) {
    std::vector<std::string> names(raw_header.size(), "_");
    for (const std::string& name : columns) names[header_column[name]] = name;
    notes->push_back(source + ": columns " + JoinItems(items) + " taken by name from the header (" +
                     std::to_string(columns.size()) + " of its " + std::to_string(raw_header.size()) +
                     " columns; the others are not used)");
    return names;
  }
  throw std::invalid_argument(
      where + ColumnLabel(conflict, raw_header[conflict]) + ": the header names this column '" + header[conflict] +
      "' but the columns list names it '" + columns[conflict] + "'" +
      (absent.empty() ? "" : " (and the header has no column '" + absent + "')") +
      ": with a header that uses idbench's names, leave the columns list out, or give one that agrees with the "
      "header (\"_\" skips a column) or names fewer columns, all found in the header (they are then matched by name)");
}

}  // namespace

std::string FormatJointLogCsv(const JointLog& log) {
  const int n = log.n_dof();
  const bool derivatives = log.has_derivatives();
  const bool torques = log.tau.size() > 0;
  std::string out = "t";
  for (const char* prefix : {"q", "qd", "qdd", "tau"}) {
    if (!derivatives && prefix[1] == 'd') continue;
    if (!torques && prefix[0] == 't') continue;
    for (int j = 1; j <= n; ++j) out += "," + std::string(prefix) + std::to_string(j);
  }
  out += '\n';
  out.reserve(out.size() + static_cast<size_t>(log.n_samples()) * static_cast<size_t>(4 * n + 1) * 24);
  for (int s = 0; s < log.n_samples(); ++s) {
    AppendShortest(&out, log.t[s]);
    auto row = [&](const Eigen::MatrixXd& m) {
      for (int j = 0; j < n; ++j) {
        out.push_back(',');
        AppendShortest(&out, m(s, j));
      }
    };
    row(log.q);
    if (derivatives) {
      row(log.qd);
      row(log.qdd);
    }
    if (torques) row(log.tau);
    out.push_back('\n');
  }
  return out;
}

bool JointLogFormat::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (angle_unit != "rad" && angle_unit != "deg") return fail("--angle-unit: expected rad or deg, got '" + angle_unit + "'");
  if (static_cast<int>(drive_gains.size()) > kMaxJoints) {
    return fail("--drive-gains: " + std::to_string(drive_gains.size()) + " gains, at most " + std::to_string(kMaxJoints));
  }
  // |K| within [kMinDriveGain, kMaxDriveGain]; a negative gain is a drive
  // whose current is logged with the opposite sign, but not every drive.
  for (size_t j = 0; j < drive_gains.size(); ++j) {
    const double k = std::abs(drive_gains[j]);
    if (!std::isfinite(drive_gains[j]) || k < kMinDriveGain || k > kMaxDriveGain) {
      return fail("drive_gains: joint " + std::to_string(j + 1) + ": expected a gain of magnitude " +
                  Shortest(kMinDriveGain) + " to " + Shortest(kMaxDriveGain) + " N m/A, got " + Shortest(drive_gains[j]));
    }
  }
  if (!drive_gains.empty() && std::all_of(drive_gains.begin(), drive_gains.end(), [](double k) { return k < 0.0; })) {
    return fail("drive_gains: every gain is negative, which turns every joint's torque around (a robot lifting "
                "against gravity would read as pushing down); a negative gain is for a drive whose current is logged "
                "with the opposite sign, as `gains` reports it; give the gains' magnitudes, or check the currents' signs");
  }
  if (columns.empty()) return true;
  std::vector<std::string> names;
  try {
    names = ExpandColumnNames(columns);
  } catch (const std::invalid_argument& e) {
    return fail(e.what());
  }
  std::map<std::string, int> seen;
  for (size_t c = 0; c < names.size(); ++c) {
    const std::string where = "--columns: column " + std::to_string(c + 1) + " ('" + names[c] + "')";
    ColumnTarget target{};
    if (names[c].empty()) {
      return fail("--columns: column " + std::to_string(c + 1) + " is empty (two commas in a row, or a comma at an "
                  "end?); name every column, \"_\" skips one");
    }
    if (!ParseColumnName(names[c], &target)) {
      return fail(where + ": unknown; expected t, q<j>, qd<j>, qdd<j>, tau<j>, i<j>, a range such as q1..q6, or _");
    }
    if (target.kind >= 0 && target.joint >= kMaxJoints) return fail(where + ": joint above " + std::to_string(kMaxJoints));
    if (names[c] != "_" && !seen.emplace(names[c], static_cast<int>(c)).second) return fail(where + ": repeated");
  }
  if (!seen.count("t")) return fail("--columns: no 't' column");
  return true;
}

bool JointLogFormat::IsValidFor(int n_dof, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!drive_gains.empty() && static_cast<int>(drive_gains.size()) != n_dof) {
    return fail("--drive-gains: " + std::to_string(drive_gains.size()) + " gains, the robot has " +
                std::to_string(n_dof) + " joints");
  }
  if (columns.empty()) return true;
  const std::vector<std::string> names = ExpandColumnNames(columns);
  for (size_t c = 0; c < names.size(); ++c) {
    ColumnTarget target{};
    if (ParseColumnName(names[c], &target) && target.kind > 0 && target.joint >= n_dof) {
      return fail("--columns: column " + std::to_string(c + 1) + " ('" + names[c] + "'): joint " +
                  std::to_string(target.joint + 1) + " but the robot has " + std::to_string(n_dof) + " joints");
    }
  }
  return true;
}

std::vector<std::string> ExpandColumnNames(const std::vector<std::string>& items) {
  std::vector<std::string> names;
  auto add = [&](const std::string& name) {
    if (static_cast<int>(names.size()) >= JointLogFormat::kMaxColumns) {
      throw std::invalid_argument("--columns: more than " + std::to_string(JointLogFormat::kMaxColumns) + " columns");
    }
    names.push_back(name);
  };
  for (const std::string& item : items) {
    const size_t dots = item.find("..");
    if (dots == std::string::npos) {
      add(item);
      continue;
    }
    // A range: <prefix><a>..<prefix><b>, a <= b.
    ColumnTarget first{}, last{};
    const std::string a = item.substr(0, dots), b = item.substr(dots + 2);
    if (!ParseColumnName(a, &first) || !ParseColumnName(b, &last) || first.kind <= 0 || first.kind != last.kind ||
        last.joint < first.joint) {
      throw std::invalid_argument("--columns: '" + item + "': expected a range such as q1..q6 (same prefix, first <= last)");
    }
    if (last.joint - first.joint >= JointLogFormat::kMaxColumns) {
      throw std::invalid_argument("--columns: '" + item + "': more than " + std::to_string(JointLogFormat::kMaxColumns) +
                                  " columns");
    }
    for (int j = first.joint; j <= last.joint; ++j) add(kKindPrefix[first.kind] + std::to_string(j + 1));
  }
  return names;
}

RecordedJointLog ParseRecordedJointLog(const std::string& text, const RobotModel& model, const std::string& source,
                                       const JointLogFormat& format, TorqueColumns torques) {
  const int n_dof = model.n_dof();
  auto fail = [&](int line, const std::string& what) -> void {
    throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
  };
  std::string why;
  if (!format.IsValid(&why) || !format.IsValidFor(n_dof, &why)) throw std::invalid_argument(why);
  // A UTF-8 byte order mark (spreadsheets write one) is not part of the
  // first column's name.
  const std::string_view kBom = "\xef\xbb\xbf";
  std::istringstream in(text.starts_with(kBom) ? text.substr(kBom.size()) : text);
  CheckLineLengths(text, source);
  std::string line;
  int line_number = 0;

  // The first non-blank line: the header, or data when --columns names them.
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  if (line_number == 0 || line.find_first_not_of(" \t\r") == std::string::npos) {
    fail(std::max(line_number, 1), format.columns.empty() ? "empty file, expected a header line" : "empty file");
  }
  const std::vector<std::string> first_fields = SplitFields(line);
  const bool header = !AllNumbers(first_fields);
  const bool named = !format.columns.empty();
  if (!named && !header) {
    fail(line_number, "the first line is data (all numbers), not a header naming the columns: pass --columns with "
                      "the names in file order, e.g. --columns t,q1..q" + std::to_string(n_dof) + ",qd1..qd" +
                      std::to_string(n_dof) + ",i1..i" + std::to_string(n_dof) + " (_ skips a column)");
  }
  // The name of each file column: the header's (q.<joint name> read as that
  // joint's number), the columns list's, or both reconciled.
  RecordedJointLog out;
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
        fail(line_number, ColumnLabel(c, first_fields[c]) + ": the header names joint " +
                              std::to_string(target.joint + 1) + " but " + model.name() + " has " +
                              std::to_string(n_dof) + " joints: is this a log of another robot?");
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
      fail(line_number, "missing column 'q" + std::to_string(most + 1) + "' (robot has " + std::to_string(n_dof) +
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
                                       source, line_number, &out.notes);
  }
  const int header_line = named ? 0 : line_number;  // where column problems are reported (0: --columns)
  auto fail_columns = [&](const std::string& what) -> void {
    if (named) throw std::invalid_argument(source + ": --columns: " + what);
    fail(header_line, what);
  };
  if (static_cast<int>(names.size()) > JointLogFormat::kMaxColumns) {
    fail_columns(std::to_string(names.size()) + " columns, at most " + std::to_string(JointLogFormat::kMaxColumns));
  }

  // Every column named once, from a known set, of a joint the robot has.
  std::map<std::string, int> column_of;
  std::vector<ColumnTarget> targets;
  for (size_t c = 0; c < names.size(); ++c) {
    const std::string& name = names[c];
    const std::string where = ColumnLabel(c, name);
    ColumnTarget target{};
    if (!ParseColumnName(name, &target)) {
      fail_columns(where + ": unknown column; expected t, q1..q" + std::to_string(n_dof) +
                   ", qd*, qdd*, tau*, i* (motor current)" + (named ? ", or _" : ""));
    }
    if (name != "_" && !column_of.emplace(name, static_cast<int>(c)).second) fail_columns(where + ": repeated");
    if (target.kind > 0 && target.joint >= n_dof) {
      fail_columns(where + ": joint " + std::to_string(target.joint + 1) + " but the robot has " +
                   std::to_string(n_dof) + " joints");
    }
    targets.push_back(target);
  }

  // Required columns, and each other kind as a complete set or not at all.
  auto has = [&](const std::string& name) { return column_of.count(name) > 0; };
  auto complete = [&](const char* prefix) {
    const std::string p(prefix);
    int count = 0;
    for (int j = 1; j <= n_dof; ++j) count += has(p + std::to_string(j));
    if (count == 0 || count == n_dof) return count == n_dof;
    for (int j = 1; j <= n_dof; ++j) {
      if (!has(p + std::to_string(j))) {
        if (has(p + "1")) {
          fail_columns("missing column '" + p + std::to_string(j) + "': give all of " + p + "1.." + p +
                       std::to_string(n_dof) + " or none");
        }
        break;
      }
    }
    for (int j = 2; j <= n_dof; ++j) {
      if (has(p + std::to_string(j))) {
        fail_columns("column '" + p + std::to_string(j) + "' without " + p + "1: give all of " + p + "1.." + p +
                     std::to_string(n_dof) + " or none");
      }
    }
    return false;
  };
  if (!has("t")) fail_columns("missing column 't'");
  for (int j = 1; j <= n_dof; ++j) {
    if (!has("q" + std::to_string(j))) {
      fail_columns("missing column 'q" + std::to_string(j) + "' (robot has " + std::to_string(n_dof) + " joints)");
    }
  }
  const bool has_qd = complete("qd"), has_qdd = complete("qdd"), has_tau = complete("tau"), has_i = complete("i");
  const std::string n_str = std::to_string(n_dof);
  bool use_tau = has_tau, use_i = false;
  switch (torques) {
    case TorqueColumns::kRequired:
      if (!format.drive_gains.empty()) {
        if (!has_i) fail_columns("--drive-gains given but the log has no motor currents i1..i" + n_str);
        use_i = true;
        use_tau = false;
        if (has_tau) out.warnings.push_back(source + ": tau columns ignored: --drive-gains given, tau = K·i from i1..i" + n_str);
      } else if (!has_tau) {
        if (has_i) {
          fail_columns("the log has motor currents i1..i" + n_str + " but no tau: pass --drive-gains K1,...,K" + n_str +
                       " (tau = K·i; `idbench gains` estimates them)");
        }
        fail_columns("missing column 'tau1' (robot has " + n_str + " joints)");
      }
      break;
    case TorqueColumns::kOptional:
      break;
    case TorqueColumns::kCurrents:
      if (!has_i) fail_columns("missing column 'i1': drive gains need the motor currents i1..i" + n_str);
      use_i = true;
      use_tau = false;
      break;
  }

  // Data lines: with --columns, fields after the named ones are ignored.
  const bool degrees = format.degrees();
  const double to_rad = degrees ? std::numbers::pi / 180.0 : 1.0;
  std::vector<std::vector<double>> rows;
  const size_t t_column = static_cast<size_t>(column_of["t"]);
  if (named && header) {
    // The first line is a header that --columns overrides: skipped.
  } else if (named) {
    in.clear();
    in.str(text.starts_with(kBom) ? text.substr(kBom.size()) : text);  // the first line is data: read it again
    line_number = 0;
  }
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = SplitFields(line);
    if (named ? fields.size() < names.size() : fields.size() != names.size()) {
      fail(line_number, std::to_string(fields.size()) + " fields, expected " + (named ? "at least " : "") +
                            std::to_string(names.size()));
    }
    std::vector<double> values(names.size(), 0.0);
    for (size_t c = 0; c < names.size(); ++c) {
      if (targets[c].kind < 0) continue;
      const std::string& f = fields[c];
      const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), values[c]);
      const std::string where = ColumnLabel(c, names[c]);
      if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) fail(line_number, where + ": '" + PrintableText(f) + "' is not a number");
      if (!std::isfinite(values[c])) fail(line_number, where + ": " + f + " is not finite");
      if (targets[c].kind >= 1 && targets[c].kind <= 3) values[c] *= to_rad;
      if (targets[c].kind == 1) {
        const JointLimits& limits = model.link(targets[c].joint).limits;
        if (values[c] < limits.q_min || values[c] > limits.q_max) {
          fail(line_number, where + ": " + f + (degrees ? " deg (" + Shortest(values[c]) + " rad)" : " rad") +
                                " is outside joint " + std::to_string(targets[c].joint + 1) + "'s limits [" +
                                std::to_string(limits.q_min) + ", " + std::to_string(limits.q_max) + "] rad");
        }
      }
    }
    const double t = values[t_column];
    if (!rows.empty() && !(t > rows.back()[t_column])) {
      fail(line_number, "column " + std::to_string(t_column + 1) + " ('t'): time " + std::to_string(t) +
                            " does not increase");
    }
    rows.push_back(std::move(values));
    out.lines.push_back(line_number);
  }
  if (rows.empty()) fail(line_number, named && !header ? "no data lines" : "no data lines after the header");

  // Columns into the log's matrices; currents × gains into tau.
  const int n_samples = static_cast<int>(rows.size());
  JointLog& log = out.log;
  log.t.resize(n_samples);
  log.q.resize(n_samples, n_dof);
  if (has_qd) log.qd.resize(n_samples, n_dof);
  if (has_qdd) log.qdd.resize(n_samples, n_dof);
  if (use_tau || use_i) log.tau.resize(n_samples, n_dof);
  Eigen::MatrixXd* matrices[] = {nullptr, &log.q, &log.qd, &log.qdd, use_tau ? &log.tau : nullptr,
                                 use_i ? &log.tau : nullptr};
  const bool scale = use_i && torques == TorqueColumns::kRequired;
  out.torque_from_currents = scale;
  for (int s = 0; s < n_samples; ++s) {
    for (size_t c = 0; c < targets.size(); ++c) {
      const double v = rows[static_cast<size_t>(s)][c];
      const ColumnTarget& target = targets[c];
      if (target.kind == 0) {
        log.t[s] = v;
      } else if (target.kind > 0 && matrices[target.kind]) {
        (*matrices[target.kind])(s, target.joint) =
            target.kind == 5 && scale ? format.drive_gains[static_cast<size_t>(target.joint)] * v : v;
      }
    }
  }
  WarnIfRadiansReadAsDegrees(format, source, &out);
  return out;
}

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
  WarnIfRadiansReadAsDegrees(format, source, &out);
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
