// idbench.design: an excitation trajectory, with a progress callback; Ctrl-C
// stops it and keeps the best design so far, as on the command line.
#include <atomic>
#include <csignal>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "bindings.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench::python {
namespace {

// SIGINT sets the flag while the design runs.
std::atomic<bool> g_design_stop{false};
extern "C" void RequestDesignStop(int) { g_design_stop = true; }

struct DesignOutput {
  double value = 0.0, initial_value = 0.0;
  double cond = 0.0, initial_cond = 0.0;
  bool feasible = false;
  bool stopped = false;
  bool usable = false;     // DesignResult::usable(): feasible and better than its start point
  std::string rejection;   // why not ("" when usable)
  std::string trajectory_json, trajectory_csv, design_json, summary;
};

// progress must be callable as progress(start, evaluations, best_value,
// feasible): TypeError before any work otherwise.
void CheckProgressCallback(const py::object& progress) {
  if (progress.is_none()) return;
  if (!PyCallable_Check(progress.ptr())) {
    throw py::type_error("progress: expected a callable progress(start, evaluations, best_value, feasible), got " +
                         std::string(py::str(py::type::of(progress).attr("__name__"))));
  }
  py::object signature;
  try {
    signature = py::module_::import("inspect").attr("signature")(progress);
  } catch (const py::error_already_set&) {
    return;  // no signature to check (some built-ins): called as is
  }
  try {
    signature.attr("bind")(0, 0, 0.0, false);
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    throw py::type_error("progress: expected a callable taking (start, evaluations, best_value, feasible), got one "
                         "with the signature " + std::string(py::str(signature)) + ": " + e.what());
  }
}

DesignOutput ToDesignOutput(const RobotModel& model, const DesignCommandOptions& options,
                            const DesignCommandReport& report) {
  const DesignResult& result = report.result;
  DesignOutput out;
  out.value = result.value;
  out.initial_value = result.initial_value;
  out.cond = result.final.cond;
  out.initial_cond = result.initial.cond;
  out.feasible = result.check.feasible();
  out.stopped = result.stopped;
  out.usable = result.usable();
  out.rejection = result.Rejection();
  out.trajectory_json = FormatTrajectoryJson(result.trajectory);
  out.trajectory_csv = FormatDesignTrajectoryCsv(model, options, report);
  out.design_json = FormatDesignJson(model, options, report);
  out.summary = FormatDesignSummary(options, report);
  return out;
}

DesignOutput Design(const Robot& robot, DesignCommandOptions options, const py::object& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const RobotModel& model = *robot.model;
  if (!options.IsValidFor(model, &why)) throw std::invalid_argument(why);
  CheckProgressCallback(progress);
  DesignControl control;
  control.stop = &g_design_stop;
  // An exception raised by progress (KeyboardInterrupt included) stops the
  // design and is raised again here: it may not cross the worker threads.
  std::mutex callback_mutex;
  std::optional<py::error_already_set> callback_error;
  std::atomic<bool> callback_failed{false};
  if (!progress.is_none()) {
    control.progress = [&](const DesignProgress& p) {
      if (callback_failed) return;
      py::gil_scoped_acquire acquire;
      try {
        progress(p.start, p.evaluations, p.best_value, p.feasible);
      } catch (py::error_already_set& e) {
        const std::lock_guard<std::mutex> lock(callback_mutex);
        if (!callback_failed.exchange(true)) callback_error.emplace(std::move(e));
        g_design_stop = true;
      }
    };
  }
  g_design_stop = false;
  const std::vector<JointLimits> limits = DesignLimits(model, options);
  options.design.actuators = DesignActuatorLimits(model, options, robot.transmission);
  std::optional<DesignCommandReport> report;
  {
    py::gil_scoped_release release;
    void (*previous)(int) = std::signal(SIGINT, RequestDesignStop);
    try {
      report = RunDesign(model, options, limits, control);
    } catch (...) {
      std::signal(SIGINT, previous);
      if (!callback_failed) throw;
    }
    std::signal(SIGINT, previous);
  }
  if (callback_failed) throw *callback_error;  // the GIL is held again here
  // No design: raised as the command line's exit codes are chosen (the
  // module's translator spells the fields as keywords). Settings that admit
  // no motion are wrong input (ValueError, exit 2); a search that found
  // nothing feasible or only a motion that leaves parameters unexcited, or a
  // cell whose obstacles leave no room, failed (RuntimeError, exit 1).
  switch (report->status()) {
    case DesignStatus::kFeasible:
      break;
    case DesignStatus::kNoMotionPossible:
      throw std::invalid_argument(report->result.infeasibility.explanation);
    case DesignStatus::kInfeasible:
    case DesignStatus::kNoRoom:
    case DesignStatus::kNotExcited:
      throw std::runtime_error(report->result.infeasibility.explanation);
  }
  return ToDesignOutput(model, options, *report);
}

void BindDesignResult(py::module_& m) {
  py::class_<DesignOutput>(m, "DesignResult")
      .def_readonly("value", &DesignOutput::value)
      .def_readonly("initial_value", &DesignOutput::initial_value)
      .def_readonly("cond", &DesignOutput::cond, "cond(W) of the design on its grid")
      .def_readonly("initial_cond", &DesignOutput::initial_cond)
      .def_readonly("feasible", &DesignOutput::feasible, "Within every limit at the check rate")
      .def_readonly("stopped", &DesignOutput::stopped, "Stopped early (Ctrl-C): the best design so far")
      .def_readonly("usable", &DesignOutput::usable,
                    "Feasible and better than its start point (the command line writes trajectory.csv only then)")
      .def_readonly("rejection", &DesignOutput::rejection, "Why the design is not usable ('' when it is)")
      .def_readonly("trajectory_json", &DesignOutput::trajectory_json, "trajectory.json")
      .def_readonly("trajectory_csv", &DesignOutput::trajectory_csv, "trajectory.csv")
      .def_readonly("design_json", &DesignOutput::design_json, "design.json")
      .def_readonly("summary", &DesignOutput::summary, "What design prints");
}

}  // namespace

void BindDesign(py::module_& m) {
  BindDesignResult(m);
  const DesignCommandOptions design_defaults;
  m.def(
      "design",
      [](const Robot& robot, const std::string& model, const std::vector<std::string>& friction,
         const std::string& criterion, const std::string& algorithm, int harmonics, double f0, double duration,
         bool rest_to_rest, int samples, int starts, unsigned seed, int threads, int max_evaluations,
         double max_time, double margin, double clearance, const std::string& limits, double rate,
         const std::string& csv_columns, double ramp, const std::vector<double>& home, const std::string& transmission,
         const std::string& scene, const py::object& base_pose, const std::vector<std::string>& given,
         const py::object& progress) {
        DesignCommandOptions options;
        options.robot = robot.source;
        options.model = EnumArgument(kIdentificationModelNames, model);
        options.friction = friction;
        if (!criterion.empty()) options.criterion = EnumArgument(kDesignCriterionNames, criterion);
        options.algorithm = EnumArgument(kDesignAlgorithmNames, algorithm);
        options.design.harmonics = harmonics;
        options.design.f0 = f0;
        options.design.duration = duration;
        options.design.rest_to_rest = rest_to_rest;
        options.design.samples = samples;
        options.design.starts = starts;
        options.design.seed = seed;
        options.design.threads = threads;
        options.design.max_evaluations = max_evaluations;
        options.design.max_seconds = max_time;
        options.design.margin = margin;
        options.design.clearance = clearance;
        options.limits = limits;
        options.transmission = transmission;
        options.scene = scene;
        options.design.base_pose = BasePoseArgument(base_pose);
        options.csv_rate_hz = rate;
        options.csv_columns = EnumArgument(kTrajectoryCsvColumnsNames, csv_columns);
        options.design.ramp_seconds = ramp;
        options.home = home;
        options.given = given;  // logs read as their defaults read them (no column or filter options here)
        options.quiet = true;
        options.command_line = "python: idbench.design";
        return Design(robot, options, progress);
      },
      py::arg("robot"), py::kw_only(), py::arg("model") = std::string(kIdentificationModelNames.Name(design_defaults.model)),
      py::arg("friction") = design_defaults.friction, py::arg("criterion") = std::string(),
      py::arg("algorithm") = DesignAlgorithmName(design_defaults.algorithm), py::arg("harmonics") = design_defaults.design.harmonics,
      py::arg("f0") = design_defaults.design.f0, py::arg("duration") = design_defaults.design.duration,
      py::arg("rest_to_rest") = design_defaults.design.rest_to_rest,
      py::arg("samples") = design_defaults.design.samples, py::arg("starts") = design_defaults.design.starts,
      py::arg("seed") = design_defaults.design.seed, py::arg("threads") = design_defaults.design.threads,
      py::arg("max_evaluations") = design_defaults.design.max_evaluations,
      py::arg("max_time") = design_defaults.design.max_seconds, py::arg("margin") = design_defaults.design.margin,
      py::arg("clearance") = design_defaults.design.clearance, py::arg("limits") = design_defaults.limits,
      py::arg("rate") = design_defaults.csv_rate_hz, py::arg("csv_columns") = std::string(kTrajectoryCsvColumnsNames.Name(design_defaults.csv_columns)),
      py::arg("ramp") = design_defaults.design.ramp_seconds, py::arg("home") = design_defaults.home,
      py::arg("transmission") = design_defaults.transmission, py::arg("scene") = design_defaults.scene,
      py::arg("base_pose") = py::none(), py::arg("given") = design_defaults.given, py::arg("progress") = py::none(),
      "Designs an excitation trajectory (as `idbench design`). transmission: \"urdf\" or a file, through which "
      "the limits file's \"actuators\" (motor-side qd_max, tau_max) are kept. scene: the cell's JSON file (obstacles, "
      "floor), kept clear of; given=[paths]: logs the robot already has (or designed trajectories), the criterion being "
      "that of their union with the new motion (summary and design_json add the predicted sigma); base_pose=(x, y, z, roll, pitch, yaw) mounts the robot (a cell whose obstacles leave no "
      "room raises RuntimeError, explained per obstacle; settings that admit no motion raise ValueError). progress(start, evaluations, best_value, feasible) "
      "is called as the starts run (TypeError before any work if it cannot be called so; an exception it raises "
      "stops the design and is raised again); Ctrl-C stops and returns the best design so far (stopped = True).");
}

}  // namespace idbench::python
