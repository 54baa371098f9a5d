#include "idbench/workbench/reports/report_command.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/json_input.h"

namespace idbench {

RunOptions RunOptionsFromResultsJson(const std::string& text, const std::string& source) {
  const nlohmann::json j = ParseJsonInput(text, source);
  const auto get = [&](const char* key, auto* value) {
    if (!j.contains(key)) throw std::invalid_argument(source + ": key '" + key + "': missing");
    try {
      j.at(key).get_to(*value);
    } catch (const nlohmann::json::exception&) {
      throw std::invalid_argument(source + ": key '" + key + "': wrong type");
    }
  };
  RunOptions options;
  get("robot", &options.robot);
  get("motion", &options.motion);
  if (options.motion == "paper") get("accel_deg_s2", &options.accel_deg_s2);
  get("duration", &options.duration);
  get("dt", &options.dt);
  get("sample_times", &options.sample_times);
  get("command", &options.command_line);
  size_t n_steps = 0;
  get("n_steps", &n_steps);
  options.all_samples = options.sample_times.size() == n_steps;
  if (options.all_samples) options.sample_times.clear();
  return options;
}

}  // namespace idbench
