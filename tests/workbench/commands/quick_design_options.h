// A design that runs in a fraction of a second: 3 harmonics of 0.2 Hz, 60
// samples, 2 starts on one thread, no clearance check, quiet.
#pragma once

#include <string>

#include "idbench/workbench/commands/design_command.h"

namespace idbench::testing {

inline DesignCommandOptions QuickDesignOptions(const std::string& robot) {
  DesignCommandOptions options;
  options.robot = robot;
  options.friction = {"viscous", "coulomb"};
  options.design.harmonics = 3;
  options.design.f0 = 0.2;
  options.design.samples = 60;
  options.design.starts = 2;
  options.design.threads = 1;
  options.design.clearance = -1.0;
  options.quiet = true;
  return options;
}

}  // namespace idbench::testing
