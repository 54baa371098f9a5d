// Trajectory files (docs/formats/trajectories.md), and --trajectory as a
// built-in name or a file.
//
// JSON, one motion family with its coefficients:
//   {"family": "fourier", "f0": Hz, "duration": s, "rest_to_rest": bool,
//    "q0": [rad × n], "a": [[rad/s × H] × n], "b": [[rad/s × H] × n]}
//   {"family": "constant-acceleration", "duration": s,
//    "q0": [rad × n], "qd0": [rad/s × n], "qdd": [rad/s² × n]}
// CSV, samples at a controller rate: the joint-log columns without torques,
//   t, q1..qn, qd1..qdn, qdd1..qddn  (qd, qdd optional),
// or with the robot's joint names, t, q.<name1>..q.<namen>, qd.<name1>.., qdd.<name1>..
// (what `design` writes), read back as a SampledTrajectory.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/excitation/sampled_trajectory.h"

namespace idbench {

// The JSON of a FourierSeriesTrajectory or ConstantAccelerationTrajectory,
// numbers in their shortest round-trip form. Throws std::invalid_argument for
// any other family (a sampled or reversed motion has no coefficients).
std::string FormatTrajectoryJson(const Trajectory& trajectory);

// Parses the JSON of a trajectory for a robot with n_dof joints; `source` names
// the file in messages. Throws std::invalid_argument "source: key 'k': what" for
// invalid JSON, an unknown family, a missing, unknown or mistyped key, sizes
// that do not match n_dof (or a and b with different H), f0 <= 0 or duration <= 0.
std::unique_ptr<Trajectory> ParseTrajectoryJson(const std::string& text, int n_dof, const std::string& source);

// Throws std::invalid_argument naming --rate when a trajectory CSV of
// `duration` [s] at `rate_hz` would not fit the memory budget
// (idbench/engine/resource_limits.h), or the rate is not > 0 and finite.
void CheckTrajectoryCsvRate(double duration, double rate_hz, int n_dof);

// Samples at t = k/rate_hz for k = 0..⌊duration·rate_hz⌋ (a last sample within
// 1e-9 of the end counts), columns t, q1..qn, qd1..qdn, qdd1..qddn (without
// derivatives: t, q1..qn). With joint_names (n_dof of them) the columns are
// named q.<name>, qd.<name>, qdd.<name>. Throws std::invalid_argument unless
// rate_hz > 0 and finite, for a count of names other than n_dof, or a name
// that is empty or holds a comma, quote or line break.
std::string FormatTrajectoryCsv(const Trajectory& trajectory, double rate_hz, bool derivatives = true,
                                const std::vector<std::string>& joint_names = {});

// Parses a trajectory CSV with the joint-log parser (header names q.<joint
// name> etc. read as the joint's number q<j>; an unknown joint name throws
// "source:line: column c ('q.x'): no joint 'x' in <robot>"; same messages,
// "source:line: column c ('name'): what"; positions within the joint limits;
// tau columns allowed and ignored) into its interpolation: quintic Hermite
// when qd and qdd are given, else the natural cubic spline. At least 2 samples.
SampledTrajectory ParseTrajectoryCsv(const std::string& text, const RobotModel& model, const std::string& source);

// --trajectory: a built-in motion name (MakeBuiltinMotion with `builtin`) or a
// path ending in .json or .csv, which brings its own duration. Throws
// std::invalid_argument naming the argument and listing the built-in names for
// an unknown name or extension, "path: cannot read the file", or the parse error.
std::unique_ptr<Trajectory> LoadTrajectoryArg(const std::string& name_or_path, const RobotModel& model,
                                              const BuiltinMotionOptions& builtin);

// Whether LoadTrajectoryArg reads `name_or_path` as a file (it ends in .json or .csv).
bool IsTrajectoryFile(const std::string& name_or_path);

}  // namespace idbench
