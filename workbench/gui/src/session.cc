#include "idbench/gui/session.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/engine/robot_library.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/formats/limits_file.h"
#include "idbench/workbench/reports/report_command.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/reports/message_list.h"

namespace idbench::gui {
namespace {

constexpr const char* kJobNames[kJobKinds] = {"design", "simulate", "identify", "per-body", "compare", "report",
                                               "payload"};

}  // namespace

const char* JobName(JobKind kind) { return kJobNames[static_cast<int>(kind)]; }

std::optional<JobKind> ParseJobName(const std::string& name) {
  for (int k = 0; k < kJobKinds; ++k)
    if (name == kJobNames[k]) return static_cast<JobKind>(k);
  return std::nullopt;
}

Session::Session(const SessionOptions& options) : out_dir(options.out_dir) {
  // Small, quick defaults for an interactive session; the structs are the CLI's.
  design.quiet = true;
  design.design.harmonics = 3;
  design.design.f0 = 0.2;
  design.design.samples = 100;
  design.design.starts = 1;
  design.design.threads = 1;
  design.design.max_evaluations = 100;
  simulate.sensors.tau_noise = {0.05};
  compare.samples = 100;
  compare.trials = 5;
  compare.tau_noise = {0.05};
  per_body.figure = false;
  payload.out_dir = OutPath("payload");
  payload.command_line = "gui: Payload tab";
  if (!LoadRobot(options.robot)) {
    // The session needs a robot: fall back to the first built-in.
    LoadRobot(BuiltinRobotNames().front());
  }
}

Session::~Session() {
  for (BackgroundJob& j : jobs_) j.RequestStop();
}

bool Session::LoadRobot(const std::string& name_or_path) {
  if (any_running()) {
    Error("cannot change the robot while a job runs; stop it or wait");
    return false;
  }
  try {
    UrdfLoadResult loaded = idbench::LoadRobot(name_or_path);
    model_ = std::make_shared<const RobotModel>(std::move(loaded.model));
    robot_transmission_ = std::move(loaded.transmission);
    for (const std::string& w : CollapseRepeatedMessages(loaded.warnings)) Info("warning: " + w);
  } catch (const std::exception& e) {
    Error(e.what());
    return false;
  }
  robot_source_ = name_or_path;
  design.robot = simulate.robot = identify.robot = compare.robot = name_or_path;
  ResetLimits();
  design_report_.reset();
  log_.reset();
  identify_report_.reset();
  fit_torques_.reset();
  held_out_torques_.reset();
  compare_report_.reset();
  per_body_result_.reset();
  {
    const std::lock_guard<std::mutex> lock(curve_mutex_);
    curve_.clear();
  }
  motion = "paper";
  RebuildBuiltinMotion();
  Info("robot " + model_->name() + ": " + std::to_string(model_->n_dof()) + " joints");
  return true;
}

void Session::ResetLimits() { limits = RobotLimits(*model_); }

void Session::FillMissingLimits() {
  for (JointLimits& l : limits) {
    if (!std::isfinite(l.q_min)) l.q_min = fill_limits.q_min;
    if (!std::isfinite(l.q_max)) l.q_max = fill_limits.q_max;
    if (!std::isfinite(l.qd_max)) l.qd_max = fill_limits.qd_max;
    if (!std::isfinite(l.qdd_max)) l.qdd_max = fill_limits.qdd_max;
    if (!std::isfinite(l.tau_max)) l.tau_max = fill_limits.tau_max;
  }
}

bool Session::any_running() const {
  for (const BackgroundJob& j : jobs_)
    if (j.running()) return true;
  return false;
}

bool Session::StartJob(JobKind kind, BackgroundJob::Work work) {
  if (!job(kind).Start(std::move(work))) {
    Error(std::string(JobName(kind)) + " is already running");
    return false;
  }
  return true;
}

// ---- Design ---------------------------------------------------------------

void Session::StartDesign() {
  std::string why;
  design.robot = robot_source_;
  if (!design.IsValid(&why)) return Error("design: " + why);
  // The joint limits are the table's; the motors' are the limits file's
  // "actuators" through design.transmission, as the command line reads them.
  DesignCommandOptions options = design;
  try {
    options.design.actuators = DesignActuatorLimits(*model_, design, robot_transmission_);
  } catch (const std::exception& e) {
    return Error(std::string("design: ") + e.what());
  }
  {
    const std::lock_guard<std::mutex> lock(curve_mutex_);
    curve_.clear();
    start_best_.assign(static_cast<size_t>(std::max(design.design.starts, 1)),
                       std::numeric_limits<double>::infinity());
  }
  // The job works on copies: the panels may keep editing.
  StartJob(JobKind::kDesign, [this, model = model_, options = std::move(options),
                              table = limits](const std::atomic<bool>& stop) {
    DesignControl control;
    control.stop = &stop;
    control.progress = [this](const DesignProgress& p) {
      const std::lock_guard<std::mutex> lock(curve_mutex_);
      if (p.start < 0 || p.start >= static_cast<int>(start_best_.size())) return;
      start_best_[static_cast<size_t>(p.start)] = std::min(start_best_[static_cast<size_t>(p.start)], p.best_value);
      double best = std::numeric_limits<double>::infinity();
      for (double v : start_best_) best = std::min(best, v);
      if (std::isfinite(best)) curve_.push_back(best);
    };
    auto report = std::make_shared<DesignCommandReport>(RunDesign(*model, options, table, control));
    return std::function<void()>([this, report] {
      if (report->status() != DesignStatus::kFeasible) {  // no design: the last one stays
        return Error(std::string(JobName(JobKind::kDesign)) + " failed: " + report->result.infeasibility.explanation);
      }
      design_report_ = std::move(*report);
      const DesignResult& r = design_report_->result;
      {
        // The curve ends at the result (progress comes every 20 evaluations).
        const std::lock_guard<std::mutex> lock(curve_mutex_);
        if (curve_.empty() || curve_.back() != r.value) curve_.push_back(r.value);
      }
      char line[256];
      std::snprintf(line, sizeof line, "design: criterion %.6g -> %.6g, cond %.4g -> %.4g, %d evaluations in %.2f s%s",
                    r.initial_value, r.value, r.initial.cond, r.final.cond, r.evaluations, r.wall_seconds,
                    r.stopped ? " (stopped)" : "");
      Info(line);
      if (!r.check.feasible()) Error("design violates limits at " + std::to_string(r.check.rate_hz) + " Hz:\n" + r.check.Explain());
      else if (!r.usable()) Error("design is not usable: " + r.Rejection() + " (it is not exported)");
      SelectMotion("designed");
    });
  });
}

void Session::StopDesign() { job(JobKind::kDesign).RequestStop(); }

std::vector<double> Session::DesignCurve() const {
  const std::lock_guard<std::mutex> lock(curve_mutex_);
  return curve_;
}

// ---- Motions --------------------------------------------------------------

void Session::RebuildBuiltinMotion() {
  const std::string name = motion == "designed" ? "" : motion;
  const std::string key = name + "/" + std::to_string(builtin_duration) + "/" + std::to_string(model_->n_dof());
  if (!name.empty() && key != builtin_motion_key_) {
    try {
      builtin_motion_ = MakeBuiltinMotion(name, model_->n_dof(), builtin_duration,
                                          simulate.paper_accel_deg_s2 * std::numbers::pi / 180.0);
      builtin_motion_key_ = key;
    } catch (const std::exception& e) {
      Error(e.what());
      builtin_motion_.reset();
      builtin_motion_key_.clear();
    }
  }
  ++motion_version_;
}

void Session::SelectMotion(const std::string& name) {
  motion = name;
  RebuildBuiltinMotion();
}

const Trajectory* Session::current_motion() const {
  if (motion == "designed") return design_report_ ? &design_report_->result.trajectory : nullptr;
  return builtin_motion_.get();
}

std::string Session::OutPath(const std::string& file) const { return (std::filesystem::path(out_dir) / file).string(); }

std::string Session::WriteDesignedTrajectory() {
  EnsureOutputDirectory(out_dir);
  const std::string path = OutPath("trajectory.json");
  WriteFileAtomically(path, FormatTrajectoryJson(design_report_->result.trajectory));
  return path;
}

// ---- Experiment -----------------------------------------------------------

void Session::StartSimulate() {
  SimulateOptions options = simulate;
  options.robot = robot_source_;
  options.base_pose = design.design.base_pose;  // the session's one mounting (the Design tab's base pose)
  try {
    if (motion == "designed") {
      if (!design_report_) return Error("simulate: no designed motion yet; run the design or pick a built-in motion");
      options.trajectory = WriteDesignedTrajectory();
    } else {
      options.trajectory = motion;
      options.duration = builtin_duration;
    }
    options.out = OutPath("log.csv");
    EnsureOutputDirectory(out_dir);
  } catch (const std::exception& e) {
    return Error(std::string("simulate: ") + e.what());
  }
  std::string why;
  if (!options.IsValid(&why)) return Error("simulate: " + why);
  StartJob(JobKind::kSimulate, [this, model = model_, options](const std::atomic<bool>&) {
    auto log = std::make_shared<JointLog>(SimulateJointLog(*model, options));
    WriteFileAtomically(options.out, FormatJointLogCsv(*log));
    return std::function<void()>([this, log, path = options.out] {
      log_ = std::move(*log);
      identify.data = path;
      simulated_log_ = path;
      Info("simulate: " + std::to_string(log_->n_samples()) + " samples written to " + path);
    });
  });
}

void Session::StartIdentify() {
  IdentifyOptions options = identify;
  options.robot = robot_source_;
  options.base_pose = design.design.base_pose;  // the session's one mounting (the Design tab's base pose)
  // The Log tab shows the controller and reference only for the estimators
  // that re-simulate the loop; kept for them, not used by the others.
  if (!IsClosedLoopEstimator(options.estimator)) options.controller = options.reference = "";
  if (options.data.empty()) return Error("identify: no joint log yet; simulate first, or open a recorded log in the Log tab");
  // The checks of `idbench identify`, against the loaded robot too.
  std::string why;
  if (!options.IsValid(&why) || !options.format.IsValidFor(model_->n_dof(), &why) ||
      !options.plausibility.IsValidFor(*model_, &why))
    return Error("identify: " + why);
  // Mounted as the command line mounts it (gravity seen from the base); the
  // report keeps references to it, so the session keeps it with the report.
  auto mounted = std::make_shared<const RobotModel>(MountRobot(*model_, options.base_pose));
  {
    const std::lock_guard<std::mutex> lock(identify_progress_mutex_);
    identify_progress_ = {0.0, "starting"};
  }
  StartJob(JobKind::kIdentify, [this, model = mounted, options](const std::atomic<bool>& stop) {
    // RunIdentify's stages fill 90 % of the bar, the predicted torques the rest.
    constexpr double kIdentifyShare = 0.9;
    auto show = [this](double fraction, const std::string& stage) {
      const std::lock_guard<std::mutex> lock(identify_progress_mutex_);
      identify_progress_ = {fraction, stage};
    };
    IdentifyControl control;
    control.stop = &stop;
    control.progress = [&](const IdentifyProgress& p) { show(kIdentifyShare * p.fraction, p.stage); };
    auto report = std::make_shared<IdentifyReport>(RunIdentify(*model, options, control));
    auto cancelled = std::function<void()>([this] { Info("identify: cancelled; the previous identification is kept"); });
    if (report->status == IdentifyStatus::kCancelled) return cancelled;
    // The torque plots: measured against predicted, on the fit log and the held-out one.
    const double n_plots = report->held_out_prepared ? 2.0 : 1.0;
    StreamObserver observer;
    observer.stop = &stop;
    double plot = 0.0;
    observer.progress = [&](double f) {
      show(kIdentifyShare + (1.0 - kIdentifyShare) * (plot + f) / n_plots, "predicting the torques of the plots");
    };
    std::shared_ptr<TorqueSeries> fit, held_out;
    try {
      fit = std::make_shared<TorqueSeries>(PredictIdentifiedTorques(*model, options, *report, false, &observer));
      plot = 1.0;
      if (report->held_out_prepared)
        held_out = std::make_shared<TorqueSeries>(PredictIdentifiedTorques(*model, options, *report, true, &observer));
    } catch (const StreamStopped&) {
      return cancelled;
    }
    show(1.0, "done");
    return std::function<void()>([this, model, report, options, fit, held_out] {
      identify_report_ = std::move(*report);
      identified_with_ = options;
      identified_model_ = model;
      fit_torques_ = std::move(*fit);
      if (held_out) held_out_torques_ = std::move(*held_out);
      else held_out_torques_.reset();
      for (const std::string& w : identify_report_->warnings) Info("warning: " + w);
      const JointTorqueIdentification& id = identify_report_->identification;
      char line[256];
      std::snprintf(line, sizeof line, "identify: %d base parameters, %d determined by the log (rank), cond(W) %.4g, "
                    "torque error %.3g%%", id.base.n_base(), id.linear.rank, id.linear.cond,
                    100.0 * id.fit.relative_error);
      Info(line);
      if (identify_report_->validation) {
        std::snprintf(line, sizeof line, "identify: held-out torque error %.3g%% (%s)",
                      100.0 * identify_report_->validation->relative_error, options.validate.c_str());
        Info(line);
      }
    });
  });
}

void Session::CancelIdentify() { job(JobKind::kIdentify).RequestStop(); }

IdentifyProgress Session::identify_progress() const {
  const std::lock_guard<std::mutex> lock(identify_progress_mutex_);
  return identify_progress_;
}

std::vector<IdentifiedRow> Session::IdentifiedRows() const {
  std::vector<IdentifiedRow> rows;
  if (!identify_report_) return rows;
  const JointTorqueIdentification& id = identify_report_->identification;
  for (int k = 0; k < id.base.n_base(); ++k) {
    IdentifiedRow row;
    row.name = id.base.names[static_cast<size_t>(k)];
    row.model_value = id.beta_model[k];
    const bool identifiable = id.linear.identifiable[static_cast<size_t>(k)];
    row.identified = identifiable ? id.beta[k] : std::numeric_limits<double>::quiet_NaN();  // no number
    row.relative_error = row.model_value != 0.0 ? (row.identified - row.model_value) / std::abs(row.model_value)
                                                : std::numeric_limits<double>::quiet_NaN();
    row.sigma_percent = id.linear.rel_sigma_percent[k];
    row.status = ClassifyParameter(row.identified, id.linear.sigma[k]);
    rows.push_back(row);
  }
  return rows;
}

std::vector<std::string> Session::UnexcitedParameters() const {
  std::vector<std::string> names;
  if (!identify_report_) return names;
  const JointTorqueIdentification& id = identify_report_->identification;
  for (int s : id.base.unexcited) names.push_back(id.standard_names[static_cast<size_t>(s)]);
  return names;
}

// ---- Per-body experiment and report ---------------------------------------

void Session::StartPerBody() {
  RunOptions options = per_body;
  options.robot = robot_source_;
  options.out_dir = out_dir;
  options.figure = options.report = false;
  try {
    if (motion == "designed") {
      if (!design_report_) return Error("per-body: no designed motion yet; run the design or pick a built-in motion");
      options.motion = WriteDesignedTrajectory();
      options.duration = design_report_->result.trajectory.duration();
    } else {
      options.motion = motion;
      options.duration = builtin_duration;
    }
  } catch (const std::exception& e) {
    return Error(std::string("per-body: ") + e.what());
  }
  std::string why;
  if (!options.IsValid(&why)) return Error("per-body: " + why);
  StartJob(JobKind::kPerBody, [this, model = model_, options](const std::atomic<bool>&) {
    auto result = std::make_shared<PerBodyIdentificationResult>(RunExperiment(*model, options).identification);
    return std::function<void()>([this, result] {
      per_body_result_ = std::move(*result);
      char line[256];
      std::snprintf(line, sizeof line, "per-body: %d samples, largest relative error %.3g (%s)",
                    per_body_result_->n_samples, per_body_result_->max_rel_error,
                    per_body_result_->max_rel_error_at.c_str());
      Info(line);
    });
  });
}

void Session::StartReport() {
  if (!identify_report_) return Error("report: nothing identified yet");
  // "truth" only for the log the GUI simulated itself; a recorded one is "measured".
  const LogOrigin origin = identified_with_.data == simulated_log_ ? LogOrigin::kSimulated : LogOrigin::kRecorded;
  StartJob(JobKind::kReport, [this, model = identified_model_, options = identified_with_, report = *identify_report_,
                              dir = out_dir, origin](const std::atomic<bool>&) {
    EnsureOutputDirectory(dir);
    WriteFilesAtomically(FormatReportFiles(MakeIdentifyReportContent(*model, options, report, origin), dir));
    return std::function<void()>(
        [this, dir] { Info("report written to " + (std::filesystem::path(dir) / "report.html").string()); });
  });
}

// ---- Compare --------------------------------------------------------------

void Session::StartCompare() {
  CompareOptions options = compare;
  options.robot = robot_source_;
  options.trajectories.clear();
  try {
    if (design_report_) {
      options.trajectories.push_back(WriteDesignedTrajectory());
      options.duration = design_report_->result.trajectory.duration();
    } else {
      options.duration = builtin_duration;
    }
  } catch (const std::exception& e) {
    return Error(std::string("compare: ") + e.what());
  }
  for (const std::string& name : compare_builtins) options.trajectories.push_back(name);
  options.scene = design.scene;  // the cell and the mounting of the Design tab
  options.base_pose = design.design.base_pose;
  options.out_dir = out_dir;
  std::string why;
  if (!options.IsValid(&why)) return Error("compare: " + why);
  StartJob(JobKind::kCompare, [this, model = model_, options](const std::atomic<bool>&) {
    auto report = std::make_shared<CompareReport>(RunCompare(*model, options));
    return std::function<void()>([this, report] {
      compare_report_ = std::move(*report);
      Info("compare: " + std::to_string(compare_report_->motions.size()) + " motions");
    });
  });
}

// ---- Jobs -----------------------------------------------------------------

void Session::Poll() { CollectJobs(false); }

void Session::WaitForJobs() { CollectJobs(true); }

void Session::CollectJobs(bool wait) {
  for (int k = 0; k < kJobKinds; ++k) {
    std::function<void()> apply;
    std::string error;
    if (!(wait ? jobs_[k].Wait(&apply, &error) : jobs_[k].Collect(&apply, &error))) continue;
    if (!error.empty()) {
      Error(std::string(kJobNames[k]) + " failed: " + error);
    } else if (apply) {
      try {
        apply();
      } catch (const std::exception& e) {
        Error(std::string(kJobNames[k]) + ": " + e.what());
      }
    }
  }
}

// ---- Export ---------------------------------------------------------------

bool Session::Export(const std::string& file, const std::function<std::string()>& content) {
  try {
    EnsureOutputDirectory(out_dir);
    const std::string path = OutPath(file);
    WriteFileAtomically(path, content());
    Info("exported " + path);
    return true;
  } catch (const std::exception& e) {
    Error(std::string("export: ") + e.what());
    return false;
  }
}

// A designed motion a robot would run is exported only when the design is
// usable (feasible at 1 kHz and better than its start), as `idbench design`
// writes it.
bool Session::DesignedMotionExportable() {
  if (!design_report_) {
    Error("export: no designed motion yet (built-in motions are named, not exported)");
    return false;
  }
  if (!design_report_->result.usable()) {
    Error("export: the design is not usable, nothing written: " + design_report_->result.Rejection());
    return false;
  }
  return true;
}

bool Session::ExportTrajectoryJson() {
  if (!DesignedMotionExportable()) return false;
  return Export("trajectory.json", [&] { return FormatTrajectoryJson(design_report_->result.trajectory); });
}

bool Session::ExportTrajectoryCsv() {
  const Trajectory* t = current_motion();
  if (!t) {
    Error("export: no motion selected");
    return false;
  }
  if (motion == "designed" && !DesignedMotionExportable()) return false;
  return Export("trajectory.csv", [&] { return FormatTrajectoryCsv(*t, design.csv_rate_hz); });
}

bool Session::ExportIdentifiedModel() {
  if (!identify_report_) {
    Error("export: nothing identified yet");
    return false;
  }
  // As `idbench identify` writes them: the diagnostics always, the robot model when the verdict allows.
  const IdentifyOptions& options = identified_with_;
  const IdentifyReport& report = *identify_report_;
  const RobotModel& model = *identified_model_;
  if (!Export("identified.json", [&] { return FormatIdentifiedJson(model, options, report); })) return false;
  if (!WritesRobotModel(options, report)) {  // the verdict refuses it (issue 20)
    Error("export: " + RefusedModelMessage(options, report));
    return false;
  }
  return Export("identified.urdf", [&] { return FormatIdentifiedUrdf(model, options, report); }) &&
         Export("identified.xml", [&] { return FormatIdentifiedMjcf(model, options, report); }) &&
         Export("joints.yaml", [&] { return FormatJointDynamicsYaml(model, options, report); });
}

// ---- Messages -------------------------------------------------------------

void Session::Info(const std::string& text) { messages_.push_back({SessionMessage::Level::kInfo, text}); }
void Session::Error(const std::string& text) { messages_.push_back({SessionMessage::Level::kError, text}); }

std::string Session::last_error() const {
  for (auto it = messages_.rbegin(); it != messages_.rend(); ++it)
    if (it->level == SessionMessage::Level::kError) return it->text;
  return "";
}

}  // namespace idbench::gui
