// Constants and message formatting shared by the excitation design's
// sources (internal to excitation/src).
#pragma once

#include <cstdio>
#include <limits>
#include <string>

namespace idbench::internal {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFeasibilityTolerance = 1e-9;  // of a normalised constraint

inline std::string Format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

}  // namespace idbench::internal
