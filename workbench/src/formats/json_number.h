// A number in the workbench's JSON files: null where it is not finite (JSON
// has no NaN or infinity), so that a reader sees "no value", never a string.
#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace idbench {

inline nlohmann::json NumberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace idbench
