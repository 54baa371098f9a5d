#include "idbench/logs/joint_log_format.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "column_names.h"
#include "number_format.h"

namespace idbench {

using internal::ColumnTarget;
using internal::kKindPrefix;
using internal::ParseColumnName;

bool JointLogFormat::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (angle_unit != "rad" && angle_unit != "deg") return fail("angle_unit: expected rad or deg, got '" + angle_unit + "'");
  if (static_cast<int>(drive_gains.size()) > kMaxJoints) {
    return fail("drive_gains: " + std::to_string(drive_gains.size()) + " gains, at most " + std::to_string(kMaxJoints));
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
    const std::string where = "columns: column " + std::to_string(c + 1) + " ('" + names[c] + "')";
    ColumnTarget target{};
    if (names[c].empty()) {
      return fail("columns: column " + std::to_string(c + 1) + " is empty (two commas in a row, or a comma at an "
                  "end?); name every column, \"_\" skips one");
    }
    if (internal::ActuatorColumn(names[c])) continue;  // refused by name when the log is read (needs a transmission)
    if (!ParseColumnName(names[c], &target)) {
      return fail(where + ": unknown; expected t, q<j>, qd<j>, qdd<j>, tau<j>, i<j>, a range such as q1..q6, or _");
    }
    if (target.kind >= 0 && target.joint >= kMaxJoints) return fail(where + ": joint above " + std::to_string(kMaxJoints));
    if (names[c] != "_" && !seen.emplace(names[c], static_cast<int>(c)).second) return fail(where + ": repeated");
  }
  if (!seen.count("t")) return fail("columns: no 't' column");
  return true;
}

bool JointLogFormat::IsValidFor(int n_dof, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!drive_gains.empty() && static_cast<int>(drive_gains.size()) != n_dof) {
    return fail("drive_gains: " + std::to_string(drive_gains.size()) + " gains, the robot has " +
                std::to_string(n_dof) + " joints");
  }
  if (transmission && !transmission->IsValid(n_dof, why)) {
    // Named where it was given (a URDF's <transmission> elements), when known.
    if (why) *why = (transmission->source.empty() ? "" : transmission->source + ": ") + "transmission." + *why;
    return false;
  }
  if (columns.empty()) return true;
  const std::vector<std::string> names = ExpandColumnNames(columns);
  for (size_t c = 0; c < names.size(); ++c) {
    ColumnTarget target{};
    if (ParseColumnName(names[c], &target) && target.kind > 0 && target.joint >= n_dof) {
      return fail("columns: column " + std::to_string(c + 1) + " ('" + names[c] + "'): joint " +
                  std::to_string(target.joint + 1) + " but the robot has " + std::to_string(n_dof) + " joints");
    }
  }
  return true;
}

std::vector<std::string> ExpandColumnNames(const std::vector<std::string>& items) {
  std::vector<std::string> names;
  auto add = [&](const std::string& name) {
    if (static_cast<int>(names.size()) >= JointLogFormat::kMaxColumns) {
      throw std::invalid_argument("columns: more than " + std::to_string(JointLogFormat::kMaxColumns) + " columns");
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
    // Actuator-side names (qm1..qm6) expand too, to be refused by name.
    if (internal::ActuatorColumn(a) && internal::ActuatorColumn(b)) {
      const size_t da = a.find_first_of("0123456789"), db = b.find_first_of("0123456789");
      const int ja = std::stoi(a.substr(da)), jb = std::stoi(b.substr(db));
      if (a.substr(0, da) == b.substr(0, db) && ja <= jb && jb - ja < JointLogFormat::kMaxColumns) {
        for (int j = ja; j <= jb; ++j) add(a.substr(0, da) + std::to_string(j));
        continue;
      }
    }
    if (!ParseColumnName(a, &first) || !ParseColumnName(b, &last) || first.kind <= 0 || first.kind != last.kind ||
        last.joint < first.joint) {
      throw std::invalid_argument("columns: '" + item + "': expected a range such as q1..q6 (same prefix, first <= last)");
    }
    if (last.joint - first.joint >= JointLogFormat::kMaxColumns) {
      throw std::invalid_argument("columns: '" + item + "': more than " + std::to_string(JointLogFormat::kMaxColumns) +
                                  " columns");
    }
    for (int j = first.joint; j <= last.joint; ++j) add(kKindPrefix[first.kind] + std::to_string(j + 1));
  }
  return names;
}

}  // namespace idbench
