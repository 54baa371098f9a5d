// `idbench run`: the paper's experiment end to end. Simulate paper6r in
// Bullet along a reference motion, identify every body with the per-body
// quaternion method, compare with the truth (paper Tables 1–3).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/simulation.h"
#include "idbench/ident/per_body_identifier.h"

namespace idbench {

struct RunOptions {
  std::string robot = "paper6r";
  std::string motion = "paper";  // "paper": hinges 1, 2 accelerate; "general": all six move; or a trajectory file
  double accel_deg_s2 = 30.0;    // hinge acceleration of the paper motion [deg/s²]
  double duration = 2.0;         // [s]
  double dt = 1e-3;              // [s]
  std::vector<double> sample_times{0.3, 0.6, 0.9, 1.2, 1.5};  // [s]
  bool all_samples = false;      // use every step instead of sample_times
  std::string out_dir = "out/run";
  std::string command_line;      // recorded in results.json
  bool figure = true;            // write figure.png, the poses at the paper's instants (--no-figure: off)
  bool report = false;           // write report.html, report.pdf and the plots (--report)

  // Minimum number of samples: the unknowns of one body (m, J11, J22, J33).
  static constexpr int kMinSamples = 4;
  static constexpr double kMaxAccelDegS2 = 1e4;

  SimulationOptions simulation() const;

  // Checks ranges and consistency (including that --out is usable); *why
  // names the bad value.
  bool IsValid(std::string* why) const;
};

// One outcome: which parameters the motion determines is part of the result
// (ParameterResult::identifiable), not a verdict on the run.
struct RunReport {
  std::string robot, motion;  // options' robot and motion, as run
  double duration = 0.0;      // [s]
  double dt = 0.0;            // [s]
  SimulationLog log;
  std::vector<int> sample_steps;
  PerBodyIdentificationResult identification;

  // Three lines: what ran (FormatRunTables' first line), how many parameters
  // were identified and which were not, and the largest relative error
  // against the paper's (its last line).
  std::string BriefReport() const;
};

// Runs the experiment (options must be valid).
// The run's motion: a built-in one (with --accel, --duration) or a
// trajectory file (trajectory_file.h), which must last at least --duration.
// Throws std::invalid_argument naming a bad file or a file that is too short.
std::unique_ptr<Trajectory> MakeRunMotion(const RobotModel& model, const RunOptions& options);

RunReport RunExperiment(const RobotModel& model, const RunOptions& options);

// The analogue of the paper's Tables 1–3 as plain text.
std::string FormatRunTables(const RunOptions& options, const RunReport& report);

// results.json (see docs/commands/run.md).
std::string FormatRunResultsJson(const RunOptions& options, const RunReport& report);

}  // namespace idbench
