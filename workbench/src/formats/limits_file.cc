#include "idbench/workbench/formats/limits_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "number_format.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/printable_text.h"

namespace idbench {

std::vector<JointLimits> RobotLimits(const RobotModel& model) {
  std::vector<JointLimits> limits;
  for (const Link& link : model.links()) limits.push_back(link.limits);
  return limits;
}

namespace {

// The limits document: an object with a "joints" array and, optionally, an "actuators" array.
nlohmann::json ParseLimitsDocument(const std::string& text, const std::string& source) {
  using nlohmann::json;
  json doc = ParseJsonInput(text, source);
  if (!doc.is_object() || !doc.contains("joints") || !doc["joints"].is_array()) {
    throw std::invalid_argument(source + ": expected an object with a \"joints\" array");
  }
  for (const auto& [key, value] : doc.items()) {
    if (key != "joints" && key != "actuators") {
      throw std::invalid_argument(source + ": unknown key '" + PrintableText(key) + "'");
    }
  }
  if (doc.contains("actuators") && !doc["actuators"].is_array()) {
    throw std::invalid_argument(source + ": actuators: expected an array (one entry per motor)");
  }
  return doc;
}

// A limit's value: a finite number > 0 (q_min and q_max: any finite number).
double LimitValue(const nlohmann::json& value, const std::string& where, const std::string& key) {
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    throw std::invalid_argument(where + "." + key + ": expected a finite number, got " + PrintableText(value.dump()));
  }
  const double v = value.get<double>();
  if (key != "q_min" && key != "q_max" && !(v > 0.0)) {
    throw std::invalid_argument(where + "." + key + ": must be > 0, got " + Shortest(v));
  }
  return v;
}

}  // namespace

std::vector<ActuatorLimit> ParseActuatorLimitsJson(const std::string& text, const std::string& source) {
  const nlohmann::json doc = ParseLimitsDocument(text, source);
  std::vector<ActuatorLimit> motors;
  if (!doc.contains("actuators")) return motors;
  const nlohmann::json& actuators = doc["actuators"];
  for (size_t k = 0; k < actuators.size(); ++k) {
    const std::string where = source + ": actuators[" + std::to_string(k) + "]";
    if (!actuators[k].is_object()) throw std::invalid_argument(where + ": expected an object");
    ActuatorLimit& l = motors.emplace_back();
    for (const auto& [key, value] : actuators[k].items()) {
      double* field = key == "qd_max" ? &l.qd_max : key == "tau_max" ? &l.tau_max : nullptr;
      if (!field) throw std::invalid_argument(where + "." + PrintableText(key) + ": unknown key (qd_max, tau_max)");
      *field = LimitValue(value, where, key);
    }
  }
  return motors;
}

std::vector<ActuatorLimit> ReadActuatorLimitsFile(const std::string& path) {
  return ParseActuatorLimitsJson(ReadInputFile(path), path);
}

std::vector<JointLimits> ParseLimitsJson(const std::string& text, const RobotModel& model, const std::string& source) {
  using nlohmann::json;
  const json doc = ParseLimitsDocument(text, source);
  const json& joints = doc.at("joints");
  if (static_cast<int>(joints.size()) != model.n_dof()) {
    throw std::invalid_argument(source + ": \"joints\" has " + std::to_string(joints.size()) + " entries, robot '" +
                                model.name() + "' has " + std::to_string(model.n_dof()) + " joints");
  }
  std::vector<JointLimits> limits = RobotLimits(model);
  for (size_t j = 0; j < joints.size(); ++j) {
    const std::string where = source + ": joints[" + std::to_string(j) + "]";
    if (!joints[j].is_object()) throw std::invalid_argument(where + ": expected an object");
    JointLimits& l = limits[j];
    for (const auto& [key, value] : joints[j].items()) {
      double* field = key == "q_min"     ? &l.q_min
                      : key == "q_max"   ? &l.q_max
                      : key == "qd_max"  ? &l.qd_max
                      : key == "qdd_max" ? &l.qdd_max
                      : key == "tau_max" ? &l.tau_max
                                         : nullptr;
      if (!field) {
        throw std::invalid_argument(where + "." + PrintableText(key) + ": unknown key (q_min, q_max, qd_max, qdd_max, tau_max)");
      }
      *field = LimitValue(value, where, key);
    }
    if (!(l.q_min < l.q_max)) {
      throw std::invalid_argument(where + ": q_min = " + Shortest(l.q_min) + " must be below q_max = " +
                                  Shortest(l.q_max) + " rad");
    }
  }
  return limits;
}

std::vector<JointLimits> ReadLimitsFile(const std::string& path, const RobotModel& model) {
  return ParseLimitsJson(ReadInputFile(path), model, path);
}

}  // namespace idbench
