// Writes a 6-joint log as CSV text the way a controller would: the chosen
// signals one sample a line, with a header of idbench's names when asked.
#pragma once

#include <Eigen/Core>
#include <cstdio>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"

namespace idbench::testing {

// Signals: "t" "q" "qd" "qdd" "tau", "i" (motor currents tau / gains) or "x"
// (a column of 7s, as a controller's extra signals).
inline std::string JointLogCsvText(const JointLog& log, const std::vector<std::string>& signals, bool header,
                                   const Eigen::VectorXd& gains = Eigen::VectorXd()) {
  std::string text;
  char number[32];
  auto add = [&](double v) {
    std::snprintf(number, sizeof(number), "%.17g", v);
    text += (text.empty() || text.back() == '\n' ? "" : ",") + std::string(number);
  };
  if (header) {
    std::string names;
    for (const std::string& s : signals) {
      if (s == "t") names += ",t";
      for (int j = 1; s != "t" && j <= 6; ++j) names += "," + s + std::to_string(j);
    }
    text += names.substr(1) + "\n";
  }
  for (int k = 0; k < log.n_samples(); ++k) {
    for (const std::string& s : signals) {
      if (s == "t") add(log.t[k]);
      for (int j = 0; s != "t" && j < 6; ++j) {
        add(s == "q" ? log.q(k, j) : s == "qd" ? log.qd(k, j) : s == "qdd" ? log.qdd(k, j) : s == "tau" ? log.tau(k, j)
            : s == "i" ? log.tau(k, j) / gains[j] : 7.0);
      }
    }
    text += "\n";
  }
  return text;
}

}  // namespace idbench::testing
