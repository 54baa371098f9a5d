#include "idbench/workbench/commands/identify_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/controller_file.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/engine/urdf.h"
#include "idbench/ident/log_identification.h"
#include "idbench/ident/prepared_log_equations.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_description.h"
#include "number_format.h"

namespace idbench {

FrictionModel IdentifyOptions::friction_model() const {
  FrictionModel f = ParseFrictionTerms(friction, nullptr).value_or(FrictionModel{});
  f.coulomb_smoothing = coulomb_smoothing;
  f.coulomb_min_speed = coulomb_min_speed;
  if (friction_side == FrictionSide::kActuator) {
    const std::optional<Transmission> t = transmission();
    if (!t) {
      throw std::invalid_argument("friction_side \"actuator\": no transmission to act through: give \"transmission\" "
                                  "in the log description, or a robot URDF with <transmission> elements");
    }
    f.actuator_from_joint = t->actuator_from_joint;
  }
  return f;
}

std::optional<Transmission> IdentifyOptions::transmission() const {
  if (IsJointLogDescriptionPath(data) && std::filesystem::is_regular_file(data)) {
    if (std::optional<Transmission> described = ReadJointLogDescription(data).transmission) return described;
  }
  return format.transmission;
}

std::vector<std::string> IdentifyOptions::data_logs() const {
  std::vector<std::string> logs{data};
  logs.insert(logs.end(), more_data.begin(), more_data.end());
  return logs;
}

LogPreparationOptions IdentifyOptions::preparation(bool with_window) const {
  LogPreparationOptions out;
  out.format = format;
  out.filter = filter;
  out.max_gap_s = max_gap_s;
  if (with_window) out.time_window = time_window;
  if (!with_window) {
    out.time_window = validate_window;
    out.window_field = "validate_window";
  }
  return out;
}

bool IdentifyOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (data.empty()) return fail("data: a joint-log CSV is required");
  if (static_cast<int>(more_data.size()) + 1 > kMaxDataLogs) {
    return fail("data: expected at most " + std::to_string(kMaxDataLogs) + " logs, got " +
                std::to_string(more_data.size() + 1));
  }
  for (size_t i = 0; i < more_data.size(); ++i) {
    if (more_data[i].empty()) return fail("data: log " + std::to_string(i + 2) + " is an empty path");
  }
  if (model == IdentificationModel::kPerBody) {
    return fail("model: per-body needs the wrench through every hinge, which a joint log does not carry; "
                "`idbench run` identifies per body from Bullet's joint feedback");
  }
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  const FrictionModel coulomb{.coulomb_smoothing = coulomb_smoothing, .coulomb_min_speed = coulomb_min_speed};
  if (std::string coulomb_why; !coulomb.IsValid(&coulomb_why)) return fail(coulomb_why);
  std::string filter_why;
  if (!filter.IsValid(&filter_why)) return fail("filter." + filter_why);
  if (!preparation(true).IsValid(why)) return false;
  if (!validate_window.empty() && validate.empty()) return fail("validate_window: given without a held-out log (validate)");
  if (!preparation(false).IsValid(why)) return false;
  std::string plausibility_why;
  if (!plausibility.IsValid(&plausibility_why)) return fail(plausibility_why);
  if (!base_pose.IsValid(why)) return false;
  const std::string name(ToString(estimator));
  if (IsClosedLoopEstimator(estimator) && controller.empty()) {
    return fail("controller: the estimator " + name + " re-simulates the closed loop: it needs the robot's "
                "controller file");
  }
  if (IsClosedLoopEstimator(estimator) && reference.empty()) {
    return fail("reference: the estimator " + name + " re-simulates the closed loop: it needs the reference the "
                "robot tracked (a built-in motion or a trajectory file)");
  }
  if (!IsClosedLoopEstimator(estimator) && (!controller.empty() || !reference.empty())) {
    return fail(std::string(controller.empty() ? "reference" : "controller") +
                ": only the closed-loop estimators (iv, didim) use it, the estimator is " + name);
  }
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

namespace {

// The stages of a run as equal shares of [0, 1] (IdentifyControl): Next()
// starts one, checking the stop flag, and gives the observer its passes report to.
class IdentifyStages {
 public:
  IdentifyStages(const IdentifyControl* control, int n_stages) : control_(control), n_stages_(n_stages) {
    if (!control_) return;
    observer_.stop = control_->stop;
    observer_.progress = [this](double fraction) { Report(static_cast<double>(stage_) + fraction); };
  }
  // Starts the next stage, named `stage`; throws StreamStopped once stop is set.
  const StreamObserver* Next(std::string stage) {
    if (!control_) return nullptr;
    if (control_->stop && control_->stop->load()) throw StreamStopped();
    if (started_) ++stage_;
    started_ = true;
    name_ = std::move(stage);
    Report(static_cast<double>(stage_));
    return &observer_;
  }
  void Done() {
    if (!control_) return;
    if (control_->stop && control_->stop->load()) throw StreamStopped();
    name_ = "done";
    Report(static_cast<double>(n_stages_));
  }

 private:
  // `stages` done of n_stages_, never less than reported before.
  void Report(double stages) {
    fraction_ = std::clamp(std::max(fraction_, stages / static_cast<double>(n_stages_)), 0.0, 1.0);
    if (control_->progress) control_->progress({fraction_, name_});
  }

  const IdentifyControl* control_;
  int n_stages_;
  int stage_ = 0;
  bool started_ = false;
  double fraction_ = 0.0;
  std::string name_;
  StreamObserver observer_;
};

// IdentifyPreparedLogs, its stages (folding each log, the solve) reported to
// `stages`. data: the logs identified together (at least one), in order.
IdentifyReport IdentifyPrepared(const RobotModel& model, const IdentifyOptions& options, std::vector<PreparedLog> data,
                                std::optional<PreparedLog> held_out, std::optional<PreparedLog> held_out_whole,
                                IdentifyStages* stages) {
  IdentifyReport report;
  JointTorqueOptions id_options;
  id_options.friction = options.friction_model();
  id_options.estimator = options.estimator;
  id_options.plausibility = options.plausibility;
  PreparedLog& first = data.front();
  id_options.parallel_filter = first.parallel_filter;
  report.filtered = id_options.parallel_filter.has_value();
  report.parallel_filter = id_options.parallel_filter;
  report.derivatives = first.derivatives;
  for (const PreparedLog& log : data) {
    report.n_samples_read += log.n_raw;
    report.notes.insert(report.notes.end(), log.notes.begin(), log.notes.end());
    report.warnings.insert(report.warnings.end(), log.warnings.begin(), log.warnings.end());
  }
  const std::string data_name = data.size() == 1 ? options.data : "data";
  // The closed loop's controller and reference, read before the logs'
  // messages take over; the re-simulation follows one reference: one log.
  std::optional<JointControllerOptions> controller;
  std::unique_ptr<Trajectory> reference;
  if (IsClosedLoopEstimator(options.estimator)) {
    CheckClosedLoopLogCount(options.estimator, data.size());
    controller = ReadControllerFile(options.controller, model.n_dof());
    reference = LoadTrajectoryArg(options.reference, model, BuiltinMotionOptions{});
  }
  const ClosedLoopInputs closed_loop{controller.value_or(JointControllerOptions{}), reference.get()};
  // Identified from the logs streamed again (IdentifyFromLogs), each stage
  // announced to `stages`.
  LogIdentification identified;
  try {
    std::vector<const PreparedLog*> logs;
    for (const PreparedLog& log : data) logs.push_back(&log);
    identified = IdentifyFromLogs(model, logs, id_options, controller ? &closed_loop : nullptr,
                                  [&](const std::string& stage) { return stages->Next(stage); });
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    bool named = what.rfind(data_name + ":", 0) == 0;
    for (const PreparedLog& log : data) named = named || what.rfind(log.path + ":", 0) == 0;
    throw std::invalid_argument(named ? what : data_name + ": " + what);
  }
  report.log = std::move(first.log);
  report.identification = std::move(identified.identification);
  report.n_samples = identified.factors.n_samples();  // what the fold kept
  report.closed_loop = identified.closed_loop;
  for (size_t i = 0; data.size() > 1 && i < data.size(); ++i) {
    const PreparedLog& log = data[i];
    report.parts.push_back(IdentifiedLogPart{log.path, identified.n_kept[i], log.n_raw,
                                             log.parallel_filter.has_value(), log.derivatives, log.parallel_filter,
                                             log.decimation, identified.cond[i]});
  }
  report.warnings.insert(report.warnings.end(), identified.warnings.begin(), identified.warnings.end());
  report.prepared = std::make_shared<PreparedLog>(std::move(first));
  if (held_out) {
    for (std::string& note : held_out->notes) report.notes.push_back(std::move(note));
    for (std::string& warning : held_out->warnings) report.warnings.push_back(std::move(warning));
    report.validation = PredictTorques(FoldPreparedLog(*held_out, model, id_options.friction, report.identification.base, {}, nullptr,
                                                       LogPreparationOptions::kMaxHeldSamples,
                                                       stages->Next("validating on " + options.validate)),
                                       report.identification.beta);
    report.held_out_log = std::move(held_out->log);
    report.held_out_filter = held_out->parallel_filter;
    report.held_out_prepared = std::make_shared<PreparedLog>(std::move(*held_out));
    if (held_out_whole) {  // the whole file, beside the window
      report.validation_whole_file =
          PredictTorques(FoldPreparedLog(*held_out_whole, model, id_options.friction, report.identification.base, {}, nullptr,
                                         LogPreparationOptions::kMaxHeldSamples,
                                         stages->Next("validating on the whole of " + options.validate)),
                         report.identification.beta);
    }
  }
  stages->Done();
  return report;
}

}  // namespace

IdentifyReport RunIdentify(const RobotModel& model, const IdentifyOptions& options, const IdentifyControl& control) {
  // The report keeps references to the model: the caller mounts it (MountRobot).
  if (!IsMountedAt(model, options.base_pose)) {
    throw std::invalid_argument("base_pose: the model's gravity is not the world's -z seen from this base; mount the "
                                "model (MountRobot)");
  }
  // Stages: each log read, then folded, the solve, and the identification
  // logs' second pass (the scores of their σ), and a closed loop's re-simulation.
  const std::vector<std::string> paths = options.data_logs();
  const int n_held_out = int(!options.validate.empty()) + int(!options.validate.empty() && !options.validate_window.empty());
  IdentifyStages stages(&control, 3 * static_cast<int>(paths.size()) + 1 + 2 * n_held_out +
                                      int(IsClosedLoopEstimator(options.estimator)));
  try {
    std::vector<PreparedLog> data;
    for (const std::string& path : paths) {
      data.push_back(PrepareJointLog(path, model, options.preparation(true), stages.Next("reading " + path)));
    }
    std::optional<PreparedLog> held_out;
    std::optional<PreparedLog> held_out_whole;
    if (!options.validate.empty()) {
      held_out = PrepareJointLog(options.validate, model, options.preparation(false),
                                 stages.Next("reading " + options.validate));
    }
    if (!options.validate.empty() && !options.validate_window.empty()) {
      IdentifyOptions whole = options;
      whole.validate_window.clear();
      held_out_whole = PrepareJointLog(options.validate, model, whole.preparation(false),
                                       stages.Next("reading the whole of " + options.validate));
    }
    return IdentifyPrepared(model, options, std::move(data), std::move(held_out), std::move(held_out_whole), &stages);
  } catch (const StreamStopped&) {
    IdentifyReport cancelled;
    cancelled.status = IdentifyStatus::kCancelled;
    return cancelled;
  }
}

IdentifyReport IdentifyPreparedLogs(const RobotModel& model, const IdentifyOptions& options,
                                    std::vector<PreparedLog> data, std::optional<PreparedLog> held_out,
                                    std::optional<PreparedLog> held_out_whole) {
  if (data.empty()) throw std::invalid_argument("data: expected at least one log");
  IdentifyStages none(nullptr, 1);
  return IdentifyPrepared(model, options, std::move(data), std::move(held_out), std::move(held_out_whole), &none);
}

IdentifyReport IdentifyPreparedLogs(const RobotModel& model, const IdentifyOptions& options, PreparedLog data,
                                    std::optional<PreparedLog> held_out, std::optional<PreparedLog> held_out_whole) {
  std::vector<PreparedLog> logs;
  logs.push_back(std::move(data));
  return IdentifyPreparedLogs(model, options, std::move(logs), std::move(held_out), std::move(held_out_whole));
}

TorqueSeries PredictIdentifiedTorques(const RobotModel& model, const IdentifyOptions& options,
                                      const IdentifyReport& report, bool held_out, const StreamObserver* observer) {
  const JointTorqueIdentification& id = report.identification;
  if (held_out && !report.held_out_prepared) throw std::invalid_argument("no held-out log was identified with");
  const PreparedLog& log = held_out ? *report.held_out_prepared : *report.prepared;
  TorqueSeries series;
  FoldPreparedLog(log, model, options.friction_model(), id.base, id.beta, &series,
                  LogPreparationOptions::kMaxHeldSamples, observer);
  return series;
}

}  // namespace idbench
