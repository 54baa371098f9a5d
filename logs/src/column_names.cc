#include "column_names.h"

#include <charconv>
#include <stdexcept>

#include "idbench/engine/printable_text.h"

namespace idbench::internal {

std::string ColumnLabel(size_t c, const std::string& name) {
  return "column " + std::to_string(c + 1) + " ('" + PrintableText(name) + "')";
}

int ActuatorPrefix(const std::string& prefix) {
  for (int k = 0; k < 4; ++k) {
    if (prefix == kActuatorPrefix[k]) return k;
  }
  return -1;
}

const char* ActuatorColumn(const std::string& name) {
  static constexpr const char* kWhat[] = {"motor position", "motor velocity", "motor torque", "motor current"};
  const size_t digits = name.find_first_of("0123456789");
  if (digits == std::string::npos || digits == 0) return nullptr;
  const int kind = ActuatorPrefix(name.substr(0, digits));
  int joint = 0;
  const char* end = name.data() + name.size();
  const auto [ptr, ec] = std::from_chars(name.data() + digits, end, joint);
  if (kind < 0 || ec != std::errc() || ptr != end || joint < 1) return nullptr;
  return kWhat[kind];
}

bool ParseActuatorColumnName(const std::string& name, ColumnTarget* target) {
  if (!ActuatorColumn(name)) return false;
  static constexpr int kKindOf[] = {1, 2, 4, 5};  // qm, qdm, taum, im
  const size_t digits = name.find_first_of("0123456789");
  const int prefix = ActuatorPrefix(name.substr(0, digits));
  int motor = 0;
  std::from_chars(name.data() + digits, name.data() + name.size(), motor);
  *target = {kKindOf[prefix], motor - 1, true};
  return true;
}

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
  // A closed loop's reference (simulate --controller writes qr1..qrn): known,
  // not an identification input, so read past as "_" is.
  if (prefix == kReferencePrefix) {
    *target = {-1, joint - 1};
    return true;
  }
  return false;
}

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

}  // namespace idbench::internal
