// `idbench compare T1 T2 …`: identifiability of candidate motions side by
// side, for one robot and identification model. Per motion: cond(W),
// normalised cond, log det, σ_min of the designed motion on its sample grid;
// the same cond for the motion Bullet actually executed (computed-torque
// tracking); predicted %σ per parameter; and the Monte-Carlo identification
// error on Bullet-simulated data with seeded noise (torque noise for the
// joint-torque model, hinge-wrench noise for the per-body model).
// Recorded joint logs (any format PrepareJointLog reads) stand beside them:
// their identifiability from the recorded states (qd, qdd measured or
// estimated by identify's zero-phase filter), and Bullet replays them.
#pragma once

#include "idbench/engine/base_pose.h"
#include "idbench/engine/enum_names.h"

#include <string>
#include <vector>

#include "idbench/excitation/design_criterion.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/excitation/excitation_design.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

struct CompareOptions {
  std::vector<std::string> trajectories;   // built-in names or .json/.csv files
  std::vector<std::string> logs;           // recorded joint logs (≥ 1 motion in all)
  // Motions the robot already has (sequential design, as design's given):
  // the motions are then ranked by cond(W) of their union with these, each
  // given second weighed as a second of the candidate (ReadGivenInformation).
  // Read as `logs` are. At most DesignCommandOptions::kMaxGiven.
  std::vector<std::string> given;
  JointLogFormat format;                   // how the logs are read
  LogFilterOptions filter{.trim_s = -1.0}; // for logs missing qd or qdd
  double max_gap_s = 0.0;                  // [s] longest step resampled; 0: 10 median steps
  std::string robot = "puma560";
  IdentificationModel model = IdentificationModel::kJointTorque;
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};
  double duration = 10.0;                  // [s] of built-in motions; files bring their own
  int samples = 250;                       // samples per motion (grid and simulated log)
  double dt = 1e-3;                        // Bullet step [s]
  std::vector<double> tau_noise;           // torque model: σ per joint or one for all [N m]; empty: DefaultTorqueNoise
  std::vector<double> wrench_noise{0.5, 0.05};  // per-body model: force [N], moment [N m] per axis
  double clearance = 0.01;                 // [m] in the limits check; negative: not checked
  std::string scene;                       // scene JSON (scene_file.h; optional): obstacles, floor
  BasePose base_pose;                      // the robot's base in the world (RunCompare mounts the model)
  int trials = 20;
  unsigned seed = 1;
  std::string out_dir = "out/compare";
  std::string command_line;

  bool IsValid(std::string* why) const;
  LogPreparationOptions preparation() const;
};

struct MotionComparison {
  std::string name;
  bool recorded = false;                // a recorded log (its span cut to whole samples·dt when simulated)
  bool simulated = true;                // false: a log too short or long to simulate (realised, MC error NaN)
  double duration = 0.0;
  Identifiability designed;             // analytic motion on the sample grid
  Identifiability realised;             // the states Bullet executed, same samples
  Identifiability with_given;           // designed, with CompareOptions::given (empty without)
  Eigen::VectorXd predicted_percent_sigma;  // 100 σ/|true| per parameter (torque model; empty otherwise);
                                            // NaN where the true value is zero up to rounding (≤ 1e-9 of the largest)
  Eigen::VectorXd predicted_sigma;          // σ per parameter, in its unit (torque model)
  double mean_relative_error = 0.0;     // Monte-Carlo mean over trials (see FormatCompareTable)
  double max_relative_error = 0.0;      // worst parameter, worst trial
  FeasibilityCheck limits;              // against the robot file's limits and the clearance at 1 kHz
  // When the motion does not excite every parameter (rank-deficient W): the
  // parameters whose columns are zero or dependent; there is then no
  // estimate, so no %σ, realised cond or Monte-Carlo error (NaN).
  std::vector<std::string> unexcited;
  int rank = 0;                         // 1 = lowest cond(W) among the motions; 0: rank-deficient
};

// The verdict on the motions compared: the first of these that holds.
enum class CompareStatus {
  kCompared,       // every motion excites every parameter and stays within the limits
  kOutsideLimits,  // some motion violates the robot file's limits or the clearance (MotionComparison::limits)
  kNotExcited,     // some motion does not excite every parameter: no estimate (MotionComparison::unexcited)
};
inline constexpr EnumNames<CompareStatus, 3> kCompareStatusNames{"status",
                                                                 {"compared", "outside limits", "not excited"}};

struct CompareReport {
  CompareStatus status = CompareStatus::kCompared;
  IdentificationModel model = IdentificationModel::kJointTorque;
  int samples = 0, trials = 0;  // per motion, as run
  std::vector<double> tau_noise;  // torque model: σ per joint (or one for all) [N m], as run
  std::vector<std::string> parameter_names;
  Eigen::VectorXd true_parameters;
  std::vector<MotionComparison> motions;
  bool ranked_with_given = false;  // ranks by cond(W) of each motion's union with the given motions
  // How the recorded logs were read, as identify says it (PreparedLog):
  std::vector<std::string> notes;     // one line per step done (window, resampling, columns), for stdout
  std::vector<std::string> warnings;  // for stderr ("is the log in radians?")

  // A few lines: the comparison's settings (FormatCompareTable's first line),
  // the best-ranked motion with its cond(W) and Monte-Carlo error, the motions
  // outside the limits and those that do not excite every parameter, and the
  // status.
  std::string BriefReport() const;
};

// Throws std::invalid_argument naming a bad trajectory or option.
CompareReport RunCompare(const RobotModel& model, const CompareOptions& options);
// The table, after the notes of how the logs were read (as identify prints them).
std::string FormatCompareTable(const CompareOptions& options, const CompareReport& report);
std::string FormatCompareJson(const CompareOptions& options, const CompareReport& report);
std::string FormatCompareCsv(const CompareReport& report);

}  // namespace idbench
