// `idbench identify`: joint-torque identification of a robot from a joint log
// (simulated or recorded), with an optional held-out log for validation.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/measurements.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/ident/closed_loop_estimators.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/logs/signal_filter.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

// Where IdentifyOptions' friction and rotor terms act (IdentifyOptions::friction_side).
enum class FrictionSide { kJoint, kActuator };
inline constexpr EnumNames<FrictionSide, 2> kFrictionSideNames{"friction_side", {"joint", "actuator"}};

struct IdentifyOptions {
  std::string robot = "puma560";   // built-in name or URDF path
  std::string data;                // joint-log CSV (required)
  // Further logs of the same robot, identified together with data: each read,
  // windowed (time_window), resampled and filtered on its own with the same
  // options, their equations stacked into one fit; σ treats each log as a
  // series of its own (ApplyPreparedLogsScoreCovariance). At most
  // kMaxDataLogs − 1.
  std::vector<std::string> more_data;
  static constexpr int kMaxDataLogs = 64;
  IdentificationModel model = IdentificationModel::kJointTorque;  // kPerBody needs hinge wrenches (idbench run)
  BasePose base_pose;              // the robot's base in the world: the model given to RunIdentify
                                   // must have its gravity (MountRobot; refused otherwise)
  TorqueEstimator estimator = TorqueEstimator::kOls;
  // The closed-loop estimators (iv, didim) re-simulate the robot's loop: its
  // controller file (controller_file.h) and the reference it tracked (a
  // built-in motion of 10 s or a trajectory file). Required by them, refused
  // with the others.
  std::string controller;
  std::string reference;
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};  // of: none, viscous, coulomb, offset, rotor
  double coulomb_smoothing = 0.0;  // [rad/s]; 0 = sign(qd)
  double coulomb_min_speed = 0.0;  // [rad/s]; Coulomb column 0 below it (FrictionModel); 0 = off
  // Where the friction and rotor terms act: kJoint (per joint, on q̇), or
  // kActuator (per motor, on θ̇m = A·q̇, into the joints through Aᵀ; needs
  // the transmission: the data's log description's, else format.transmission,
  // the robot's URDF's).
  FrictionSide friction_side = FrictionSide::kJoint;
  LogFilterOptions filter{.trim_s = -1.0};  // used when the log has no qd/qdd columns; trims 5/fc
  PlausibilitySettings plausibility;  // bounds of the physically consistent estimate
  std::string validate;            // held-out joint log (optional)
  // Reading the logs (docs/formats/joint-logs.md): format (columns, angle
  // unit, drive gains) for data and validate; time_window for data only.
  JointLogFormat format;
  std::vector<double> time_window;  // {T0, T1} [s]; empty: the whole log
  // {T0, T1} [s] of the held-out log scored as validation (e.g. its moving
  // part, without rest phases where the drives idle); empty: the whole log.
  // The whole file's error is reported beside it.
  std::vector<double> validate_window;
  double max_gap_s = 0.0;           // [s] longest step resampled; 0: 10 median steps
  // Write identified.urdf and joints.yaml also when the physically consistent
  // estimate is not fit to load (IdentificationVerdict): the user accepts it.
  bool write_unverified = false;
  std::string out_dir = "out/identify";
  std::string command_line;        // recorded in identified.json

  FrictionModel friction_model() const;
  // The transmission the data is read with: its log description's, else
  // format.transmission (the robot's); nullopt when neither gives one.
  std::optional<Transmission> transmission() const;
  // data, then more_data: every log identified from, in order.
  std::vector<std::string> data_logs() const;
  // How --data (with_window: time_window) or --validate (validate_window) is read.
  LogPreparationOptions preparation(bool with_window) const;
  // Checks the options alone; *why names the bad one.
  bool IsValid(std::string* why) const;
};

// How far a run is (IdentifyControl::progress).
struct IdentifyProgress {
  double fraction = 0.0;  // of the whole run, in [0, 1], non-decreasing; 1 when done
  std::string stage;      // what runs now, e.g. "reading log.csv", "solving (pc)"
};

// Progress and cancel of RunIdentify (the GUI's progress bar and Cancel), as
// DesignControl is the design's. The run is split into equal stages: each
// pass over a log (reading, folding its equations) and the solve; a pass
// reports per block of samples, the solve at its start and end.
struct IdentifyControl {
  const std::atomic<bool>* stop = nullptr;  // set to end the run early: IdentifyStatus::kCancelled
  std::function<void(const IdentifyProgress&)> progress;  // called on the thread running RunIdentify
};

enum class IdentifyStatus {
  kDone,
  kCancelled,  // control.stop was set: the report holds nothing else
};

// One of several logs identified together (IdentifyOptions::more_data): what
// identify says of a log, counted as IdentifyReport counts the whole.
struct IdentifiedLogPart {
  std::string path;
  Eigen::Index n_samples = 0, n_samples_read = 0;  // in the fit; read (IdentifyReport's)
  bool filtered = false;
  std::string derivatives;
  std::optional<ParallelFilter> parallel_filter;
  int decimation = 1;
  double cond = 0.0;  // cond(W) of this log's equations alone (OLS: unweighted)
};

struct IdentifyReport {
  IdentifyStatus status = IdentifyStatus::kDone;
  // As identified (after filtering, if any): every sample up to
  // LogPreparationOptions::kMaxHeldSamples, else every k-th (plots, playback).
  JointLog log;
  // The samples counted twice: those the fit used (its equations' samples:
  // after decimation and, when filtered, the filter's transient ends
  // dropped), and those read (in the time window, after resampling) before
  // either. Equal when the log is neither filtered nor decimated.
  Eigen::Index n_samples = 0;        // in the fit
  Eigen::Index n_samples_read = 0;   // read from the log
  bool filtered = false;             // qd/qdd were estimated by filtering
  std::string derivatives;           // where the identification log's qd, qdd come from
  std::vector<std::string> notes;    // how the logs were read (window, resampling), for stdout
  std::vector<std::string> warnings; // for stderr
  JointTorqueIdentification identification;
  // With IdentifyOptions::more_data: every log, in order (empty for one log).
  // n_samples, n_samples_read above are then their sums; log, prepared,
  // parallel_filter and derivatives are the first log's (plots, playback).
  std::vector<IdentifiedLogPart> parts;
  // With a closed-loop estimator (iv, didim): its iterations and verdict;
  // identification.beta and identification.linear.sigma are then its
  // estimate and σ, the rest of `linear` the OLS it started from.
  std::optional<ClosedLoopEstimate> closed_loop;
  std::optional<TorquePrediction> validation;  // on the held-out log (its validate_window, if any)
  std::optional<TorquePrediction> validation_whole_file;  // on the whole held-out log, when validate_window is set
  // What predicts the torques again (PredictTorqueSeries, the report's plots):
  std::optional<ParallelFilter> parallel_filter;   // on log's equations; set when filtered
  std::optional<JointLog> held_out_log;            // --validate, prepared as validation scored it (held as `log`)
  std::optional<ParallelFilter> held_out_filter;   // on held_out_log's equations, if any
  // The prepared logs, streamed again for the predicted torques.
  std::shared_ptr<const PreparedLog> prepared, held_out_prepared;
};

// Reads the logs and identifies. Throws std::invalid_argument naming the file,
// line and column of bad data, or the option that does not fit the data.
// Writes no file. Once control.stop is set, returns a report with status
// kCancelled (at the next block of samples, or after the solve).
IdentifyReport RunIdentify(const RobotModel& model, const IdentifyOptions& options,
                           const IdentifyControl& control = {});

// The same for logs already prepared (PrepareJointLog or
// PrepareRecordedJointLog, e.g. arrays from Python): `data` the logs
// identified together (at least one, in order); options.data, more_data and
// validate only name them in messages.
// held_out_whole: the whole held-out log, when held_out is its validate_window.
IdentifyReport IdentifyPreparedLogs(const RobotModel& model, const IdentifyOptions& options,
                                    std::vector<PreparedLog> data, std::optional<PreparedLog> held_out,
                                    std::optional<PreparedLog> held_out_whole = std::nullopt);
// One log.
IdentifyReport IdentifyPreparedLogs(const RobotModel& model, const IdentifyOptions& options, PreparedLog data,
                                    std::optional<PreparedLog> held_out,
                                    std::optional<PreparedLog> held_out_whole = std::nullopt);

// Measured and predicted torque (τ̂ = W β of the chosen estimator) on the
// identification log or the held-out one, parallel-filtered as the RMS
// numbers score them (PredictTorqueSeries), streamed (FoldPreparedLog): every
// kept equation up to LogPreparationOptions::kMaxHeldSamples, else every k-th.
// With an observer: its progress over the pass, StreamStopped once its stop is set.
TorqueSeries PredictIdentifiedTorques(const RobotModel& model, const IdentifyOptions& options,
                                      const IdentifyReport& report, bool held_out,
                                      const StreamObserver* observer = nullptr);

// Whether identified.urdf and joints.yaml are written: the verdict is fit to
// load, or options.write_unverified.
bool WritesRobotModel(const IdentifyOptions& options, const IdentifyReport& report);

// When the estimate is not fit to load: one message with the verdict, the
// binding constraints by link, the likely cause and fix, naming the options'
// fields ("plausibility.com_in_geometry = false", write_unverified), which
// each front end spells its own way (field_spelling.h). Empty when it is
// fit to load.
std::string RefusedModelMessage(const IdentifyOptions& options, const IdentifyReport& report);

// The line identify prints under its table: how σ was computed (batch
// means: blocks, samples per block), n_eff, and the factor to the
// white-residual σ, which `output` (a file name) holds as sigma_white.
std::string SigmaMethodText(const CovarianceSummary& summary, const std::string& output);
// The same for identify (identified.json).
std::string SigmaMethodText(const LinearFit& fit);

// %σ of a value as printed: 100 σ/|value|, or NaN where |value| ≤ 3σ (the
// value is indistinguishable from zero, and a ratio to it means nothing:
// σ itself, absolute, is what is known) or σ is not finite.
double RelativeSigmaPercent(double value, double sigma);

std::string FormatIdentifyTables(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report);
// identified.json (README.md).
std::string FormatIdentifiedJson(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report);
// joints.yaml: per joint, the friction, offset, rotor inertia and drive gain
// a controller loads next to identified.urdf (README.md).
std::string FormatJointDynamicsYaml(const RobotModel& model, const IdentifyOptions& options,
                                    const IdentifyReport& report);
// identified.urdf: the robot with the physically consistent standard parameters.
std::string FormatIdentifiedUrdf(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report);
// identified.xml: the same robot as MJCF (formats/mjcf_writer.h), with its
// rotor inertia (armature), viscous (damping) and Coulomb (frictionloss)
// friction; offsets have no MJCF counterpart.
std::string FormatIdentifiedMjcf(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report);

}  // namespace idbench
