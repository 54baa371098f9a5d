// `idbench design`: an excitation trajectory for a robot and identification
// model, optimised within its limits (excitation_design.h). Writes
// trajectory.json (coefficients), trajectory.csv (samples at the controller
// rate) and design.json (criterion before and after, identifiability,
// 1 kHz constraint margins, starts, evaluations, wall time).
#pragma once

#include <atomic>
#include <optional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "idbench/excitation/design_regressor.h"
#include "idbench/excitation/excitation_design.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

// trajectory.csv's columns (DesignCommandOptions::csv_columns): positions, or
// positions, velocities and accelerations.
enum class TrajectoryCsvColumns { kQ, kQQdQdd };
inline constexpr EnumNames<TrajectoryCsvColumns, 2> kTrajectoryCsvColumnsNames{"csv_columns", {"q", "q,qd,qdd"}, true};

struct DesignCommandOptions {
  std::string robot = "puma560";                     // built-in name or URDF path
  IdentificationModel model = IdentificationModel::kJointTorque;
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};  // joint-torque model's friction terms (as identify)
  // nullopt = cond for the torque model; logdet for per-body, where minimising the
  // normalised cond shrinks the motion (measured on paper6r: Monte-Carlo error
  // 4.0e-3 with cond-normalised, 2.2e-4 with cond, 9.6e-5 with logdet, 8.0e-4
  // for the paper's motion).
  std::optional<DesignCriterion> criterion;
  DesignAlgorithm algorithm = DesignAlgorithm::kSlsqp;
  std::string limits;                                // limits JSON (optional)
  std::string scene;                                 // scene JSON (scene_file.h; optional): design.scene
  // The transmission the limits file's "actuators" are given through
  // (transmission_file.h): "urdf" (the robot URDF's) or a file; "": none.
  std::string transmission;
  DesignOptions design;                              // design.base_pose: where the robot stands; RunDesign
                                                     // mounts the model it is given (MountRobot)
  double csv_rate_hz = 1000.0;                       // trajectory.csv sample rate; the re-check runs at
                                                     // the larger of it and design.check_rate_hz
  TrajectoryCsvColumns csv_columns = TrajectoryCsvColumns::kQQdQdd;  // trajectory.csv's columns
  std::vector<double> home;                          // [rad] --home (n_dof); empty: found (home_pose.h)
  bool quiet = false;                                // no progress on stderr
  // Write trajectory.json and trajectory.csv even when the design is not
  // usable (DesignResult::Rejection: infeasible, or no progress); the exit
  // code stays 1.
  bool write_trajectory_anyway = false;
  std::string out_dir = "out/design";
  std::string command_line;                          // recorded in design.json
  // Sequential design: motions the robot already has, whose union with the
  // new motion the criterion is of (ReadGivenInformation). Each a joint log
  // in any format identify reads (read as given_reading says, the whole log),
  // or a designed trajectory (design's trajectory.json or trajectory.csv:
  // information, no torques). Joint-torque model only; at most kMaxGiven.
  std::vector<std::string> given;
  LogPreparationOptions given_reading;               // format, filter, max_gap_s of the given logs
  static constexpr int kMaxGiven = 64;

  // Checks the options alone (not the robot); *why names the bad one.
  bool IsValid(std::string* why) const;
  // And against the robot: --home has one angle per joint.
  bool IsValidFor(const RobotModel& model, std::string* why) const;
  // The regressor of the chosen identification model.
  DesignRegressor MakeRegressor(const RobotModel& model) const;
  // design with criterion and algorithm parsed.
  DesignOptions Resolved() const;
};

// What RunDesign came to. A front end switches on status(): kFeasible has a
// design (result.usable() says whether to run it); otherwise
// result.infeasibility explains why there is none. The command line writes
// design.json and exits 1 for kInfeasible and kNoRoom (it ran and failed),
// exits 1 writing nothing for kNotExcited (a motion within the limits that
// leaves parameters unexcited), and treats kNoMotionPossible as wrong input
// (exit 2, nothing written).
struct DesignCommandReport {
  std::vector<JointLimits> limits;   // as used
  DesignResult result;
  std::vector<std::string> parameter_names;
  // Clearance (link_clearance.h): the pairs not checked, with the reason, and
  // the pairs held at their distance at q = 0 ("a–b ≥ 0.104 m").
  std::vector<std::string> clearance_excluded, clearance_held;
  ActuatorLimits actuators;          // as used (DesignOptions::actuators)
  DesignCriterion criterion = DesignCriterion::kLogCond;  // as used
  // With given motions (DesignCommandOptions::given): each one's part, the
  // union's numbers are result.initial/final; the given ones alone, and σ
  // per parameter predicted with them alone and with the new motion added.
  struct GivenMotion {
    std::string path;
    bool measured = true;        // a log with torques; false: a designed trajectory
    Eigen::Index n_samples = 0;  // samples its equations hold
    double duration_s = 0.0;     // [s]
    double weight = 1.0;         // per row, to the new motion's per-second weight
  };
  std::vector<GivenMotion> given;
  std::vector<std::string> given_notes;  // how the logs were read
  Identifiability given_alone;
  Eigen::VectorXd sigma_given, sigma_with_new;  // (n_parameters); +inf: undetermined
  double noise_variance = 0.0;                  // s² per design-rate row; NaN: no measured log (σ per unit s)

  DesignStatus status() const { return result.status; }
  // One line: the status, the criterion before and after, the verdict at the
  // check rate, the evaluations and wall time: "design feasible: cond 231.4 ->
  // cond 18.52, feasible at 1000 Hz, usable; 1204 evaluations in 2.31 s";
  // without a design, why not (DesignResult::Rejection): "design infeasible:
  // no feasible design: no start met the limits ...; 20 evaluations in 0.41 s".
  std::string BriefReport() const;
};

// The information of the motions `paths` (DesignCommandOptions::given) for
// `regressor` (its base parameters and friction; model mounted as the
// design's), each row weighted so that the motion counts by its duration: a
// second of it weighs as a second of a new motion sampled at
// rows_per_second (the design's samples per second): w = rows_per_second ·
// T / n, T the motion's duration and n its equations' samples (see
// docs/commands/design.md). A designed trajectory is sampled at
// kGivenTrajectoryRateHz. *motions and *notes (optional) get each motion's
// part and the logs' reading notes. Throws std::invalid_argument naming the
// file for a log that cannot be read or has too few samples.
inline constexpr double kGivenTrajectoryRateHz = 100.0;
inline constexpr Eigen::Index kMaxGivenTrajectorySamples = 1000000;
GivenInformation ReadGivenInformation(const RobotModel& model, const DesignRegressor& regressor,
                                      const std::vector<std::string>& paths, const LogPreparationOptions& reading,
                                      double rows_per_second,
                                      std::vector<DesignCommandReport::GivenMotion>* motions = nullptr,
                                      std::vector<std::string>* notes = nullptr);

// The smallest trajectory.csv rate that samples the motion: ten samples per
// period of the highest harmonic, 10 H f0 [Hz].
double MinimumCsvRate(const DesignOptions& design);

// The limits a design keeps: the --limits file's, else the robot file's.
// Throws std::invalid_argument naming a bad file.
std::vector<JointLimits> DesignLimits(const RobotModel& model, const DesignCommandOptions& options);

// The limits file's "actuators" through options.transmission (from_urdf: the
// robot URDF's transmission, for "urdf"); empty when the file has none.
// Throws std::invalid_argument naming `transmission` when actuator limits come
// without one, or a bad file, count or value (ActuatorLimits::Check).
ActuatorLimits DesignActuatorLimits(const RobotModel& model, const DesignCommandOptions& options,
                                    const std::optional<Transmission>& from_urdf);

// Runs the design of the model mounted at options.design.base_pose, in the
// cell options.scene names (read here; design.scene when empty), within the
// limits file's joint and actuator limits (DesignLimits, DesignActuatorLimits;
// from_urdf: the robot URDF's transmission); progress lines on stderr unless quiet; `stop` ends it
// early with the best feasible design so far. Throws std::invalid_argument for
// bad limits or files; when nothing feasible was found, or the design leaves
// parameters unexcited, the report says so (status(), result.infeasibility)
// and nothing of the starts is printed.
DesignCommandReport RunDesign(const RobotModel& model, const DesignCommandOptions& options,
                              const std::atomic<bool>* stop,
                              const std::optional<Transmission>& from_urdf = std::nullopt);

// The same with the joint limits given (a GUI's limit table; options.limits is not
// read; the actuator limits are options.design.actuators) and a control whose progress observer, if any, is called from the
// worker threads besides the stderr lines.
DesignCommandReport RunDesign(const RobotModel& model, const DesignCommandOptions& options,
                              const std::vector<JointLimits>& limits, const DesignControl& control);

// trajectory.csv: what the robot runs (DesignResult::RobotTrajectory, the
// ramps included) at csv_rate_hz, the columns csv_columns names, headed with
// the robot's joint names (trajectory_file.h).
std::string FormatDesignTrajectoryCsv(const RobotModel& model, const DesignCommandOptions& options,
                                      const DesignCommandReport& report);

// What design prints of a design (status() kFeasible).
std::string FormatDesignSummary(const DesignCommandOptions& options, const DesignCommandReport& report);
// design.json. When no feasible design was found (status() not kFeasible):
// the settings as for a design, "check" (the explained point's margins) and
// "infeasible": {before_search, explanation, advice}.
std::string FormatDesignJson(const RobotModel& model, const DesignCommandOptions& options,
                             const DesignCommandReport& report);

// cond, cond_normalised, log_det, sigma_min, sigma_max, rank (shared with compare).
nlohmann::json IdentifiabilityJson(const Identifiability& id);

}  // namespace idbench
