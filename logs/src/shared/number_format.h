// Numbers as idbench writes them (logs/ and the workbench, an internal header
// of both, not installed): shortest decimals that read back exactly.
#pragma once

#include <Eigen/Core>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace idbench {

inline void AppendShortest(std::string* out, double value) {
  char buffer[32];
  out->append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
}

inline std::string Shortest(double value) {
  std::string out;
  AppendShortest(&out, value);
  return out;
}

// printf-style for tables ("%.4g"); "-" for NaN and ±inf.
inline std::string Format(const char* format, double v) {
  if (!std::isfinite(v)) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

// For JSON arrays.
inline std::vector<double> ToStdVector(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace idbench
