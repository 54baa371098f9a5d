// `idbench gains`: the drive gains (torque per motor current) of every joint
// from two logs of the same robot, unloaded and with a payload of known mass
// on the last link (drive_gains.h), for `identify --drive-gains`.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/ident/drive_gains.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

struct GainsOptions {
  std::string robot = "puma560";   // built-in name or URDF path
  std::string data;                // unloaded log with currents i1..in (required)
  std::string loaded;              // the same robot with the payload (required)
  double payload_mass = 0.0;       // [kg] (required)
  JointLogFormat format;           // --columns and --angle-unit, for both logs (no drive gains: they are the unknowns)
  std::vector<double> time_window;         // {T0, T1} [s] of the unloaded log (data); empty: all of it
  std::vector<double> loaded_time_window;  // {T0, T1} [s] of the loaded log; empty: all of it
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};
  double coulomb_smoothing = 0.0;  // [rad/s]; 0 = sign(qd)
  double coulomb_min_speed = 0.0;  // [rad/s]; Coulomb column 0 below it (FrictionModel); 0 = off
  LogFilterOptions filter{.trim_s = -1.0};
  double max_gap_s = 0.0;          // [s]; 0: 10 median steps
  std::string out_dir = "out/gains";
  std::string command_line;        // recorded in gains.json

  FrictionModel friction_model() const;
  // How the unloaded (loaded = false) or the loaded log is read.
  LogPreparationOptions preparation(bool loaded = false) const;
  // Checks the options alone; *why names the bad one.
  bool IsValid(std::string* why) const;
};

struct GainsReport {
  DriveGainEstimate estimate;        // estimate.status: the verdict (estimated, not identifiable, not observed)
  std::string robot;                 // the robot's name
  std::string data, loaded;          // the logs read (options' data and loaded)
  double payload_mass = 0.0;         // [kg]
  int n_unloaded = 0, n_loaded = 0;  // samples used
  std::vector<std::string> notes;     // how the logs were read, for stdout
  std::vector<std::string> warnings;  // for stderr

  DriveGainStatus status() const { return estimate.status; }
  // Every gain determined and carried by the data: gains.json is written.
  bool good() const { return estimate.status == DriveGainStatus::kEstimated; }
  // Four lines: the logs and rank, the gains with the largest %σ, the
  // relative torque residuals, and the verdict (with its message when not good).
  std::string BriefReport() const;
};

// Reads both logs and estimates. Throws std::invalid_argument naming the file,
// line and column of bad data, or a log of more prepared samples than
// LogPreparationOptions::kMaxHeldSamples (both are held whole; refused before
// either is held, the message naming the window or decimation that fits). Gains the logs do not determine are
// report.estimate.status, not a throw.
GainsReport RunGains(const RobotModel& model, const GainsOptions& options);

// The gains with σ, and the fit of both logs.
std::string FormatGainsTable(const RobotModel& model, const GainsOptions& options, const GainsReport& report);
// gains.json: {"drive_gains": [...], "sigma": [...], ...} (docs/commands/gains.md).
std::string FormatGainsJson(const RobotModel& model, const GainsOptions& options, const GainsReport& report);

}  // namespace idbench
