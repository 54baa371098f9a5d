// The flags that say how a joint log is read and conditioned, shared by
// identify and gains (README "Joint logs"), and their field → flag spellings.
#pragma once

#include <CLI/CLI.hpp>
#include <span>
#include <string>
#include <vector>

#include "cli_command.h"
#include "idbench/logs/signal_filter.h"
#include "idbench/logs/joint_log_format.h"

namespace idbench::cli {

// Fields of JointLogFormat named in messages about reading a log.
inline constexpr FieldFlag kLogReadingSpellings[] = {{"angle_unit", "--angle-unit"},
                                                     {"torque_held", "--torque-held"},
                                                     {"topic", "--topic"},
                                                     {"columns", "--columns"},
                                                     {"drive_gains", "--drive-gains"},
                                                     {"max_gap_s", "--max-gap"},
                                                     {"filter.cutoff_hz", "--filter-cutoff"},
                                                     {"filter.order", "--filter-order"},
                                                     {"filter.decimation", "--decimate"}};

// --drive-gains K1,...,Kn: tau = K·i from a log's current columns (identify,
// payload and compare read current logs alike).
void AddDriveGainsFlag(CLI::App* command, JointLogFormat* format);

// --filter-cutoff, --filter-order: the low-pass that estimates qd, qdd from q.
void AddFilterFlags(CLI::App* command, LogFilterOptions* filter);

// The Coulomb column's two settings (FrictionModel): tanh's velocity and the
// speed below which the column is 0.
struct CoulombFields {
  double* smoothing;  // --coulomb-smoothing
  double* min_speed;  // --coulomb-min-speed
};

// --columns, --topic, --angle-unit, --friction, --coulomb-smoothing,
// --coulomb-min-speed, --filter-cutoff, --filter-order, --max-gap, filling
// these fields of the command's options. friction null (a command with its
// own --friction): no --friction or Coulomb flags (coulomb unused).
void AddLogReadingFlags(CLI::App* command, JointLogFormat* format, std::vector<std::string>* friction,
                        CoulombFields coulomb, LogFilterOptions* filter, double* max_gap_s);

}  // namespace idbench::cli
