// Numbers as the workbench writes them: shortest decimals that read back exactly.
#pragma once

#include <Eigen/Core>
#include <charconv>
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

// For JSON arrays.
inline std::vector<double> ToStdVector(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace idbench
