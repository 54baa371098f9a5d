#include "idbench/workbench/formats/controller_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/printable_text.h"

namespace idbench {
namespace {

// A gain: one finite number, or an array of them (at most kMaxValues).
std::vector<double> GainValues(const nlohmann::json& value, const std::string& where) {
  constexpr size_t kMaxValues = 1000;  // far above any robot's joints
  std::vector<double> out;
  auto number = [&](const nlohmann::json& v, const std::string& at) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      throw std::invalid_argument(at + ": expected a finite number, got " + PrintableText(v.dump()));
    }
    out.push_back(v.get<double>());
  };
  if (value.is_array()) {
    if (value.empty() || value.size() > kMaxValues) {
      throw std::invalid_argument(where + ": expected 1 to 1000 numbers, got " + std::to_string(value.size()));
    }
    for (size_t j = 0; j < value.size(); ++j) number(value[j], where + "[" + std::to_string(j) + "]");
  } else {
    number(value, where);
  }
  return out;
}

}  // namespace

JointControllerOptions ParseControllerJson(const std::string& text, const std::string& source, int n_dof) {
  const nlohmann::json doc = ParseJsonInput(text, source);
  if (!doc.is_object()) throw std::invalid_argument(source + ": expected an object with \"kp\" and \"kd\"");
  JointControllerOptions options;
  for (const auto& [key, value] : doc.items()) {
    const std::string where = source + ": ." + key;
    if (key == "kp") {
      options.kp = GainValues(value, where);
    } else if (key == "kd") {
      options.kd = GainValues(value, where);
    } else if (key == "ki") {
      options.ki = GainValues(value, where);
    } else if (key == "tau_max") {
      options.tau_max = GainValues(value, where);
    } else if (key == "feedforward") {
      if (value != "model" && value != "none") {
        throw std::invalid_argument(where + ": expected \"model\" or \"none\", got " + PrintableText(value.dump()));
      }
      options.model_feedforward = value == "model";
    } else {
      throw std::invalid_argument(source + ": unknown key '" + PrintableText(key) +
                                  "' (expected kp, kd, ki, tau_max, feedforward)");
    }
  }
  std::string why;
  if (!options.IsValid(n_dof, &why)) throw std::invalid_argument(source + ": " + why);
  return options;
}

JointControllerOptions ReadControllerFile(const std::string& path, int n_dof) {
  return ParseControllerJson(ReadInputFile(path), path, n_dof);
}

}  // namespace idbench
