// `idbench payload`: the mass, centre of mass and inertia of a payload fixed
// to one link of an identified robot, from a log with the payload and,
// optionally, an unloaded log of the same motion that cancels the robot
// file's errors (payload_estimator.h). Writes payload.json and, when the
// verdict is good (or write_unverified), payload.urdf.xml: a fixed joint and
// a link to append to the robot's URDF (docs/commands/payload.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/payload_estimator.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

struct PayloadOptions {
  std::string robot;                // identified URDF path or built-in name (required)
  std::string loaded_log;           // log with the payload: t, q, (qd, qdd), tau (required)
  std::string unloaded_log;         // log of the same motion without it; empty: the robot file's model is subtracted
  std::string payload_link;         // URDF name of the link carrying the payload; empty: the last link of the chain
  JointLogFormat format;            // columns, angle unit and drive gains, for both logs
  BasePose base_pose;               // the robot's base in the world: the model must be mounted so (MountRobot)
  std::vector<double> time_window;           // {T0, T1} [s] of the loaded log; empty: all of it
  std::vector<double> unloaded_time_window;  // {T0, T1} [s] of the unloaded log; empty: all of it
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};  // the robot's joint terms (two logs)
  double coulomb_smoothing = 0.0;   // [rad/s]; 0 = sign(qd)
  double coulomb_min_speed = 0.0;   // [rad/s]; Coulomb column 0 below it (FrictionModel); 0 = off
  LogFilterOptions filter{.trim_s = -1.0};
  double max_gap_s = 0.0;           // [s]; 0: 10 median steps
  double max_relative_sigma = PayloadEstimatorOptions{}.max_relative_sigma;  // verdict: σ / scale at most (payload_estimator.h)
  double max_projection_distance = PayloadEstimatorOptions{}.max_projection_distance;  // verdict: [σ]
  bool write_unverified = false;    // write payload.urdf.xml even when the verdict is not good (all identifiable)
  std::string out_dir = "out/payload";
  std::string command_line;         // recorded in payload.json

  FrictionModel friction_model() const;
  // How the loaded (unloaded = false) or the unloaded log is read.
  LogPreparationOptions preparation(bool unloaded = false) const;
  // Checks the options alone; *why names the field.
  bool IsValid(std::string* why) const;
  // And against the robot: payload_link names a link of its chain.
  bool IsValidFor(const RobotModel& model, std::string* why) const;
  // The estimator's options for `model` (after IsValidFor).
  PayloadEstimatorOptions estimator(const RobotModel& model) const;
};

struct PayloadSummary {
  PayloadStatus status = PayloadStatus::kEstimated;
  std::string message;              // why the verdict is not good, and what to change
  PayloadEstimate estimate;
  std::string link_name;            // the payload's link
  int n_loaded = 0, n_unloaded = 0; // samples used (n_unloaded 0 with one log)
  std::vector<std::string> notes;     // how the logs were read, for stdout
  std::vector<std::string> warnings;  // for stderr

  // Every quantity determined, σ small, a physical body.
  bool good() const { return status == PayloadStatus::kEstimated; }
  // One line: the mass, COM and the verdict.
  std::string BriefReport() const;
};

// Reads the logs and estimates. Throws std::invalid_argument naming the file,
// line and column of bad data, or an option that does not fit the robot.
// Parameters the logs do not determine are summary.status, not a throw.
PayloadSummary RunPayload(const RobotModel& model, const PayloadOptions& options);
// The same on logs already prepared (e.g. arrays from Python); options'
// loaded_log and unloaded_log only name them.
PayloadSummary RunPayloadOnLogs(const RobotModel& model, const PayloadOptions& options, PreparedLog loaded,
                                std::optional<PreparedLog> unloaded);

// Whether payload.urdf.xml is written: a good verdict, or write_unverified
// with every quantity determined.
bool WritesPayloadUrdf(const PayloadOptions& options, const PayloadSummary& summary);

// The quantities with σ, what is not identifiable and why, and the verdict.
std::string FormatPayloadTable(const PayloadOptions& options, const PayloadSummary& summary);
// payload.json: {"mass", "com", "inertia", "sigma", "verdict", "not_identifiable", ...}.
std::string FormatPayloadJson(const RobotModel& model, const PayloadOptions& options, const PayloadSummary& summary);
// payload.urdf.xml: a fixed joint from the payload's link to a link holding
// the payload's inertial, to paste into the robot's <robot> element.
std::string FormatPayloadUrdf(const RobotModel& model, const PayloadOptions& options, const PayloadSummary& summary);

// The files to write into options.out_dir: payload.json always, payload.urdf.xml
// when WritesPayloadUrdf.
std::vector<std::pair<std::filesystem::path, std::string>> PayloadFiles(const RobotModel& model,
                                                                       const PayloadOptions& options,
                                                                       const PayloadSummary& summary);

}  // namespace idbench
