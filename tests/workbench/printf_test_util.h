// A number as printf prints it: the truth a report's exactly formatted cells
// are checked against.
#pragma once

#include <cstdio>
#include <string>

namespace idbench::testing {

inline std::string Printf(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

}  // namespace idbench::testing
