// The Python module `idbench` (pybind11): the library calls the command line
// makes, on numpy arrays. Options are keyword arguments named as the command
// line's (--total-mass → total_mass); errors are raised with the command
// line's messages (ValueError: bad input or options; RuntimeError: it ran and
// failed). README.md, "Python".
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/robot_library.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/render/png_codec.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/commands/log_preparation.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/version.h"

namespace py = pybind11;

namespace idbench {
namespace {

// A robot loaded once and shared, immutable, by every call that takes it.
struct Robot {
  std::shared_ptr<const RobotModel> model;
  std::string source;                 // name or path as given
  std::vector<std::string> warnings;  // from loading the file
};

Robot LoadRobotForPython(const std::string& name_or_path, const std::map<std::string, double>& lock,
                         const std::string& tip) {
  UrdfLoadOptions load;
  load.locked_joints = lock;
  load.tip_link = tip;
  std::string why;
  if (!load.IsValid(&why)) throw std::invalid_argument(why);
  UrdfLoadResult loaded = LoadRobot(name_or_path, load);
  return Robot{std::make_shared<const RobotModel>(std::move(loaded.model)), name_or_path, std::move(loaded.warnings)};
}

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ArrayRef = Eigen::Ref<const RowMatrix>;

// An n_samples × n_dof array (a 1-D array is one joint's column) with a name for messages.
void CheckJointArray(const std::string& name, const Eigen::MatrixXd& x, Eigen::Index n_samples, int n_dof) {
  if (x.rows() != n_samples || x.cols() != n_dof) {
    throw std::invalid_argument(name + ": expected an array of " + std::to_string(n_samples) + " samples × " +
                                std::to_string(n_dof) + " joints, got " + std::to_string(x.rows()) + " × " +
                                std::to_string(x.cols()));
  }
  if (!x.allFinite()) throw std::invalid_argument(name + ": not every value is a finite number");
}

py::dict JointLogToDict(JointLog log) {
  py::dict out;
  out["t"] = std::move(log.t);
  out["q"] = std::move(log.q);
  if (log.qd.size() > 0) out["qd"] = std::move(log.qd);
  if (log.qdd.size() > 0) out["qdd"] = std::move(log.qdd);
  out["tau"] = std::move(log.tau);
  return out;
}

// A log given as a file path (read as `identify` reads it) or as a dict of arrays.
PreparedLog PrepareLogArgument(const py::object& log, const std::string& source, const RobotModel& model,
                               const LogPreparationOptions& options) {
  if (py::isinstance<py::str>(log) || py::hasattr(log, "__fspath__")) {
    return PrepareJointLog(py::str(log).cast<std::string>(), model, options);
  }
  // A dict of arrays, read as a file is (angle_unit, drive_gains, limits):
  // a 1-D array is one joint's column.
  if (!py::isinstance<py::dict>(log)) {
    throw std::invalid_argument(source + ": expected a CSV path or a dict of arrays {t, q, [qd, qdd], tau | i}");
  }
  std::map<std::string, Eigen::MatrixXd> arrays;
  for (const auto& [key, value] : log.cast<py::dict>()) {
    if (value.is_none()) continue;
    arrays[py::str(key).cast<std::string>()] = value.cast<RowMatrix>();
  }
  return PrepareRecordedJointLog(RecordedJointLogFromArrays(arrays, model, source, options.format, options.torques),
                                 source, options);
}

FrictionModel FrictionFor(const std::vector<std::string>& terms, double coulomb_smoothing) {
  std::string why;
  std::optional<FrictionModel> friction = ParseFrictionTerms(terms, &why);
  if (!friction) throw std::invalid_argument("friction: " + why);
  friction->coulomb_smoothing = coulomb_smoothing;
  return *friction;
}

// The identification's result as Python sees it: base parameters with their
// status (not identifiable: NaN, never a number), the physically consistent
// standard parameters, and the files `identify` writes, as text.
struct IdentifyResult {
  std::vector<std::string> base_names;
  Eigen::VectorXd beta, sigma, rel_sigma_percent, beta_model;
  std::vector<std::string> status;
  std::vector<std::string> standard_names;
  Eigen::VectorXd standard;  // physically consistent π
  double cond = 0.0;
  double fit_relative_error = 0.0;
  std::optional<double> validation_relative_error;
  std::optional<double> validation_whole_file_relative_error;  // with validate_window: the whole held-out log's
  py::dict torques;                     // {t, measured, predicted} on the identification log
  std::optional<py::dict> validation_torques;  // the same on the held-out log
  std::string tables, json;
  std::optional<std::string> urdf, joints_yaml;  // None when the verdict refuses the model
  py::dict verdict;  // {status, fit_to_load, message, cause, cost_excess_percent, cost_tolerance_percent, bounds_at_optimum}
  std::vector<std::string> warnings, notes;
};

IdentifyResult Identify(const Robot& robot, const py::object& data, const IdentifyOptions& options,
                        const py::object& validate) {
  const RobotModel& model = *robot.model;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (!options.format.IsValidFor(model.n_dof(), &why)) throw std::invalid_argument(why);
  if (!options.plausibility.IsValidFor(model, &why)) throw std::invalid_argument(why);
  PreparedLog prepared = PrepareLogArgument(data, options.data, model, options.preparation(true));
  std::optional<PreparedLog> held_out, held_out_whole;
  if (!validate.is_none()) held_out = PrepareLogArgument(validate, options.validate, model, options.preparation(false));
  if (!validate.is_none() && !options.validate_window.empty()) {
    IdentifyOptions whole = options;
    whole.validate_window.clear();
    held_out_whole = PrepareLogArgument(validate, options.validate, model, whole.preparation(false));
  }
  IdentifyReport report;
  {
    py::gil_scoped_release release;
    report = IdentifyPreparedLogs(model, options, std::move(prepared), std::move(held_out), std::move(held_out_whole));
  }
  const JointTorqueIdentification& id = report.identification;
  IdentifyResult r;
  r.base_names = id.base.names;
  r.beta = id.beta;
  r.sigma = id.linear.sigma;
  r.rel_sigma_percent = id.linear.rel_sigma_percent;
  for (int k = 0; k < id.base.n_base(); ++k) r.rel_sigma_percent[k] = RelativeSigmaPercent(id.beta[k], id.linear.sigma[k]);
  r.beta_model = id.beta_model;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const ParameterStatus status = ClassifyParameter(id.beta[k], id.linear.sigma[k]);
    r.status.push_back(ToString(status));
    if (status == ParameterStatus::kNotIdentifiable) r.beta[k] = r.rel_sigma_percent[k] = std::nan("");
  }
  r.standard_names = id.standard_names;
  r.standard = id.consistent.pi;
  r.cond = id.linear.cond;
  r.fit_relative_error = id.fit.relative_error;
  auto series_dict = [](TorqueSeries series) {
    py::dict out;
    out["t"] = std::move(series.t);
    out["measured"] = std::move(series.measured);
    out["predicted"] = std::move(series.predicted);
    return out;
  };
  r.torques = series_dict(PredictIdentifiedTorques(model, options, report, false));
  if (report.validation) {
    r.validation_relative_error = report.validation->relative_error;
    if (report.validation_whole_file) {
      r.validation_whole_file_relative_error = report.validation_whole_file->relative_error;
    }
    r.validation_torques = series_dict(PredictIdentifiedTorques(model, options, report, true));
  }
  r.tables = FormatIdentifyTables(model, options, report);
  r.json = FormatIdentifiedJson(model, options, report);
  if (WritesRobotModel(options, report)) {
    r.urdf = FormatIdentifiedUrdf(model, options, report);
    r.joints_yaml = FormatJointDynamicsYaml(model, options, report);
  }
  const IdentificationVerdict& v = id.verdict;
  r.verdict["status"] = ToKey(v.status);
  r.verdict["fit_to_load"] = v.fit_to_load();
  r.verdict["message"] = v.message;
  r.verdict["cause"] = v.fit_to_load() ? py::object(py::none())
                                       : py::object(py::str(InFrontEndTerms(v.cause, OptionNames::kPython)));
  r.verdict["cost_excess_percent"] = 100.0 * v.cost_excess;
  r.verdict["cost_tolerance_percent"] = 100.0 * v.cost_tolerance;
  py::list bounds;
  for (const ActiveBound& b : id.consistent.bounds_at_optimum) bounds.append(b.text);
  r.verdict["bounds_at_optimum"] = bounds;
  r.warnings = report.warnings;
  r.notes = report.notes;
  return r;
}

// Ctrl-C during a design stops it and keeps the best design so far, as on
// the command line: SIGINT sets the flag while the design runs.
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

DesignOutput Design(const Robot& robot, const DesignCommandOptions& options, const py::object& progress) {
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
  const DesignResult& result = report->result;
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
  out.trajectory_csv = FormatDesignTrajectoryCsv(model, options, *report);
  out.design_json = FormatDesignJson(model, options, *report);
  out.summary = FormatDesignSummary(options, *report);
  return out;
}

}  // namespace
}  // namespace idbench

PYBIND11_MODULE(idbench, m) {
  using namespace idbench;
  m.doc() = "idbench: excitation design and dynamic parameter identification of serial robots";
  m.attr("__version__") = Version();
  m.attr("__git_revision__") = GitRevision();
  // As the command line's exit codes: settings that admit no motion are wrong
  // input (ValueError, exit 2); a search that found nothing feasible failed
  // (RuntimeError, exit 1). Other exceptions: pybind11's mapping
  // (std::invalid_argument → ValueError, std::runtime_error → RuntimeError).
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InfeasibleDesign& e) {
      PyErr_SetString(e.before_search() ? PyExc_ValueError : PyExc_RuntimeError, e.what());
    }
  });

  py::class_<Robot>(m, "Robot", "A robot model (built-in or from a URDF file); immutable")
      .def(py::init(&LoadRobotForPython), py::arg("robot"), py::arg("lock") = std::map<std::string, double>{},
           py::arg("tip") = std::string(),
           "Loads a built-in robot ('paper6r', 'puma560') or a URDF file. lock: {joint: value} held fixed "
           "(--lock); tip: the arm's last link (--tip).")
      .def_property_readonly("name", [](const Robot& r) { return r.model->name(); })
      .def_property_readonly("n_dof", [](const Robot& r) { return r.model->n_dof(); })
      .def_property_readonly("joint_names", [](const Robot& r) {
        std::vector<std::string> names;
        for (const Link& link : r.model->links()) names.push_back(link.joint_name);
        return names;
      })
      .def_property_readonly("link_names", [](const Robot& r) {
        std::vector<std::string> names;
        for (const Link& link : r.model->links()) names.push_back(link.name);
        return names;
      })
      .def_readonly("warnings", &Robot::warnings)
      .def("__repr__", [](const Robot& r) {
        return "<idbench.Robot '" + r.model->name() + "', " + std::to_string(r.model->n_dof()) + " joints>";
      });

  py::class_<BaseParameters>(m, "BaseParameters", "The identifiable combinations β = combination · π")
      .def_readonly("names", &BaseParameters::names)
      .def_readonly("independent", &BaseParameters::independent)
      .def_readonly("combination", &BaseParameters::combination)
      .def_property_readonly("n_base", &BaseParameters::n_base);

  const std::vector<std::string> default_friction = IdentifyOptions{}.friction;
  m.def(
      "base_parameters",
      [](const Robot& robot, const std::vector<std::string>& friction, double coulomb_smoothing) {
        return ComputeBaseParameters(*robot.model, FrictionFor(friction, coulomb_smoothing));
      },
      py::arg("robot"), py::arg("friction") = default_friction, py::arg("coulomb_smoothing") = 0.0,
      "The base parameters of the joint-torque model with these friction terms (as identify)");
  m.def(
      "standard_parameters",
      [](const Robot& robot, const std::vector<std::string>& friction, double coulomb_smoothing) {
        const FrictionModel f = FrictionFor(friction, coulomb_smoothing);
        return py::make_tuple(StandardParameterNames(*robot.model, f), StandardParameters(*robot.model, f));
      },
      py::arg("robot"), py::arg("friction") = default_friction, py::arg("coulomb_smoothing") = 0.0,
      "(names, values) of the robot file's standard parameters π");
  m.def(
      "regressor",
      [](const Robot& robot, const ArrayRef& q, const ArrayRef& qd, const ArrayRef& qdd,
         const std::vector<std::string>& friction, double coulomb_smoothing, std::optional<BaseParameters> base) {
        const RobotModel& model = *robot.model;
        const FrictionModel f = FrictionFor(friction, coulomb_smoothing);
        if (!base) base = ComputeBaseParameters(model, f);
        JointLog log;
        log.q = q;
        log.qd = qd;
        log.qdd = qdd;
        CheckJointArray("q", log.q, q.rows(), model.n_dof());
        CheckJointArray("qd", log.qd, q.rows(), model.n_dof());
        CheckJointArray("qdd", log.qdd, q.rows(), model.n_dof());
        log.t = Eigen::VectorXd::LinSpaced(q.rows(), 0.0, static_cast<double>(q.rows()));
        log.tau = Eigen::MatrixXd::Zero(q.rows(), model.n_dof());
        py::gil_scoped_release release;
        return StackBaseRegressor(model, f, *base, log);
      },
      py::arg("robot"), py::arg("q"), py::arg("qd"), py::arg("qdd"), py::arg("friction") = default_friction,
      py::arg("coulomb_smoothing") = 0.0, py::arg("base") = py::none(),
      "The base regressor W stacked over the samples (n_samples × n_dof arrays in; rows sample·n_dof + joint), "
      "so that tau.reshape(-1) = W @ beta");

  py::class_<IdentifyResult>(m, "IdentifyResult")
      .def_readonly("base_names", &IdentifyResult::base_names)
      .def_readonly("beta", &IdentifyResult::beta, "Base parameters; NaN where not identifiable")
      .def_readonly("sigma", &IdentifyResult::sigma, "Standard deviations; inf where not identifiable")
      .def_readonly("rel_sigma_percent", &IdentifyResult::rel_sigma_percent)
      .def_readonly("status", &IdentifyResult::status,
                    "Per base parameter: determined, poor, indistinguishable from zero, not identifiable")
      .def_readonly("beta_model", &IdentifyResult::beta_model, "The robot file's base parameters")
      .def_readonly("standard_names", &IdentifyResult::standard_names)
      .def_readonly("standard", &IdentifyResult::standard, "Physically consistent standard parameters")
      .def_readonly("cond", &IdentifyResult::cond)
      .def_readonly("fit_relative_error", &IdentifyResult::fit_relative_error)
      .def_readonly("validation_relative_error", &IdentifyResult::validation_relative_error)
      .def_readonly("validation_whole_file_relative_error", &IdentifyResult::validation_whole_file_relative_error,
                    "with validate_window: the relative error over the whole held-out log")
      .def_readonly("torques", &IdentifyResult::torques,
                    "{t, measured, predicted} on the identification log (n_kept × n_dof; parallel-filtered as scored)")
      .def_readonly("validation_torques", &IdentifyResult::validation_torques, "The same on the held-out log")
      .def_readonly("tables", &IdentifyResult::tables, "What identify prints")
      .def_readonly("json", &IdentifyResult::json, "identified.json")
      .def_readonly("urdf", &IdentifyResult::urdf, "identified.urdf; None when the verdict refuses the model")
      .def_readonly("joints_yaml", &IdentifyResult::joints_yaml, "joints.yaml; None when the verdict refuses the model")
      .def_readonly("verdict", &IdentifyResult::verdict,
                    "Whether the physically consistent estimate is a robot model to load: status, fit_to_load, "
                    "message, cause, cost_excess_percent, cost_tolerance_percent, bounds_at_optimum")
      .def_readonly("warnings", &IdentifyResult::warnings)
      .def_readonly("notes", &IdentifyResult::notes);

  const IdentifyOptions id_defaults;
  m.def(
      "identify",
      [](const Robot& robot, const py::object& data, const std::string& estimator,
         const std::vector<std::string>& friction, double coulomb_smoothing, const py::object& validate,
         const std::vector<std::string>& columns, const std::string& angle_unit,
         const std::vector<double>& drive_gains, const std::vector<double>& time_window,
         const std::vector<double>& validate_window, double max_gap,
         double filter_cutoff, int filter_order, int decimate, const std::vector<double>& mass_range,
         double total_mass, double total_mass_tolerance, const std::string& com_bound, double prior_weight,
         double cost_tolerance, bool write_unverified) {
        IdentifyOptions options;
        options.robot = robot.source;
        options.data = py::isinstance<py::dict>(data) ? "<data arrays>" : py::str(data).cast<std::string>();
        options.validate = validate.is_none()                ? ""
                           : py::isinstance<py::dict>(validate) ? "<validate arrays>"
                                                                : py::str(validate).cast<std::string>();
        options.estimator = estimator;
        options.friction = friction;
        options.coulomb_smoothing = coulomb_smoothing;
        options.format.columns = columns;
        options.format.angle_unit = angle_unit;
        options.format.drive_gains = drive_gains;
        options.time_window = time_window;
        options.validate_window = validate_window;
        options.max_gap_s = max_gap;
        options.filter.cutoff_hz = filter_cutoff;
        options.filter.order = filter_order;
        options.filter.decimation = decimate;
        if (mass_range.size() != 2) throw std::invalid_argument("mass_range: expected (min, max) factors");
        options.plausibility.mass_factor_min = mass_range[0];
        options.plausibility.mass_factor_max = mass_range[1];
        options.plausibility.total_mass = total_mass;
        options.plausibility.total_mass_tolerance = total_mass_tolerance;
        if (com_bound != "geometry" && com_bound != "none") {
          throw std::invalid_argument("com_bound: expected geometry or none, got '" + com_bound + "'");
        }
        options.plausibility.com_in_geometry = com_bound == "geometry";
        options.plausibility.prior_weight = prior_weight;
        options.plausibility.cost_tolerance = cost_tolerance;
        options.write_unverified = write_unverified;
        options.command_line = "python: idbench.identify";
        return Identify(robot, data, options, validate);
      },
      py::arg("robot"), py::arg("data"), py::kw_only(), py::arg("estimator") = id_defaults.estimator,
      py::arg("friction") = id_defaults.friction, py::arg("coulomb_smoothing") = id_defaults.coulomb_smoothing,
      py::arg("validate") = py::none(), py::arg("columns") = std::vector<std::string>{},
      py::arg("angle_unit") = id_defaults.format.angle_unit, py::arg("drive_gains") = std::vector<double>{},
      py::arg("time_window") = std::vector<double>{}, py::arg("validate_window") = std::vector<double>{},
      py::arg("max_gap") = id_defaults.max_gap_s,
      py::arg("filter_cutoff") = id_defaults.filter.cutoff_hz, py::arg("filter_order") = id_defaults.filter.order,
      py::arg("decimate") = id_defaults.filter.decimation,
      py::arg("mass_range") = std::vector<double>{id_defaults.plausibility.mass_factor_min,
                                                  id_defaults.plausibility.mass_factor_max},
      py::arg("total_mass") = id_defaults.plausibility.total_mass,
      py::arg("total_mass_tolerance") = id_defaults.plausibility.total_mass_tolerance,
      py::arg("com_bound") = std::string("geometry"), py::arg("prior_weight") = id_defaults.plausibility.prior_weight,
      py::arg("cost_tolerance") = id_defaults.plausibility.cost_tolerance, py::arg("write_unverified") = false,
      "Identifies the robot from a joint log: a CSV path (read as `idbench identify --data`) or a dict of arrays "
      "{t, q, [qd, qdd], tau} or with i (motor currents) for drive_gains (n_samples × n_dof, angles in angle_unit; "
      "without qd/qdd they are estimated by filtering). validate_window=(T0, T1) scores only that part of the held-out "
      "log. Options as `idbench identify`'s. The result's verdict says whether the physically consistent estimate is "
      "a robot model; urdf and joints_yaml are None when it is not (unless write_unverified=True).");

  const SimulateOptions sim_defaults;
  m.def(
      "simulate",
      [](const Robot& robot, const std::string& trajectory, double duration, double paper_accel, double dt,
         double rate, const std::vector<double>& tau_noise, double q_noise, double q_resolution, bool derivatives,
         unsigned seed) {
        SimulateOptions options;
        options.robot = robot.source;
        options.trajectory = trajectory;
        options.duration = duration;
        options.paper_accel_deg_s2 = paper_accel;
        options.dt = dt;
        options.sensors.rate_hz = rate;
        options.sensors.tau_noise = tau_noise;
        options.sensors.q_noise = q_noise;
        options.sensors.q_resolution = q_resolution;
        options.sensors.record_derivatives = derivatives;
        options.sensors.seed = seed;
        std::string why;
        if (!options.IsValid(&why)) throw std::invalid_argument(why);
        if (!options.sensors.IsValid(robot.model->n_dof(), options.dt, &why)) throw std::invalid_argument(why);
        JointLog log;
        {
          py::gil_scoped_release release;
          log = SimulateJointLog(*robot.model, options);
        }
        return JointLogToDict(std::move(log));
      },
      py::arg("robot"), py::arg("trajectory") = sim_defaults.trajectory, py::kw_only(),
      py::arg("duration") = sim_defaults.duration, py::arg("paper_accel") = sim_defaults.paper_accel_deg_s2,
      py::arg("dt") = sim_defaults.dt, py::arg("rate") = sim_defaults.sensors.rate_hz,
      py::arg("tau_noise") = std::vector<double>{}, py::arg("q_noise") = sim_defaults.sensors.q_noise,
      py::arg("q_resolution") = sim_defaults.sensors.q_resolution,
      py::arg("derivatives") = sim_defaults.sensors.record_derivatives, py::arg("seed") = sim_defaults.sensors.seed,
      "Simulates the robot along a built-in motion or a trajectory file in Bullet (as `idbench simulate`); "
      "returns {t, q, [qd, qdd], tau} as numpy arrays");

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

  const DesignCommandOptions design_defaults;
  m.def(
      "design",
      [](const Robot& robot, const std::string& model, const std::vector<std::string>& friction,
         const std::string& criterion, const std::string& algorithm, int harmonics, double f0, double duration,
         bool rest_to_rest, int samples, int starts, unsigned seed, int threads, int max_evaluations,
         double max_time, double margin, double clearance, const std::string& limits, double rate,
         const std::string& csv_columns, double ramp, const std::vector<double>& home, const py::object& progress) {
        DesignCommandOptions options;
        options.robot = robot.source;
        options.model = model;
        options.friction = friction;
        options.criterion = criterion;
        options.algorithm = algorithm;
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
        options.csv_rate_hz = rate;
        options.csv_columns = csv_columns;
        options.design.ramp_seconds = ramp;
        options.home = home;
        options.quiet = true;
        options.command_line = "python: idbench.design";
        return Design(robot, options, progress);
      },
      py::arg("robot"), py::kw_only(), py::arg("model") = design_defaults.model,
      py::arg("friction") = design_defaults.friction, py::arg("criterion") = design_defaults.criterion,
      py::arg("algorithm") = design_defaults.algorithm, py::arg("harmonics") = design_defaults.design.harmonics,
      py::arg("f0") = design_defaults.design.f0, py::arg("duration") = design_defaults.design.duration,
      py::arg("rest_to_rest") = design_defaults.design.rest_to_rest,
      py::arg("samples") = design_defaults.design.samples, py::arg("starts") = design_defaults.design.starts,
      py::arg("seed") = design_defaults.design.seed, py::arg("threads") = design_defaults.design.threads,
      py::arg("max_evaluations") = design_defaults.design.max_evaluations,
      py::arg("max_time") = design_defaults.design.max_seconds, py::arg("margin") = design_defaults.design.margin,
      py::arg("clearance") = design_defaults.design.clearance, py::arg("limits") = design_defaults.limits,
      py::arg("rate") = design_defaults.csv_rate_hz, py::arg("csv_columns") = design_defaults.csv_columns,
      py::arg("ramp") = design_defaults.design.ramp_seconds, py::arg("home") = design_defaults.home,
      py::arg("progress") = py::none(),
      "Designs an excitation trajectory (as `idbench design`). progress(start, evaluations, best_value, feasible) "
      "is called as the starts run (TypeError before any work if it cannot be called so; an exception it raises "
      "stops the design and is raised again); Ctrl-C stops and returns the best design so far (stopped = True).");

  const RenderOptions render_defaults;
  m.def(
      "render",
      [](const Robot& robot, const std::string& trajectory, const std::vector<double>& times, double duration,
         double paper_accel, const std::string& layout, const std::string& size, const std::string& png) {
        RenderOptions options;
        options.robot = robot.source;
        options.trajectory = trajectory;
        if (!times.empty()) options.times = times;
        options.duration = duration;
        options.paper_accel_deg_s2 = paper_accel;
        options.layout = layout;
        options.size = size;
        std::string why;
        if (!options.IsValid(&why)) throw std::invalid_argument(why);
        const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(*robot.model, options);
        const PoseFigureOptions figure = options.figure();
        if (!figure.IsValid(motion->duration(), &why)) throw std::invalid_argument(why);
        Image image;
        {
          py::gil_scoped_release release;
          image = RenderPoseFigureImage(*robot.model, *motion, figure);
        }
        if (!png.empty()) WriteFileAtomically(png, EncodePng(image));
        py::array_t<std::uint8_t> pixels({image.height, image.width, 3});
        std::copy(image.rgb.begin(), image.rgb.end(), pixels.mutable_data());
        return pixels;
      },
      py::arg("robot"), py::arg("trajectory") = render_defaults.trajectory, py::kw_only(),
      py::arg("times") = std::vector<double>{}, py::arg("duration") = render_defaults.duration,
      py::arg("paper_accel") = render_defaults.paper_accel_deg_s2, py::arg("layout") = render_defaults.layout,
      py::arg("size") = render_defaults.size, py::arg("png") = std::string(),
      "Renders the robot at instants of a motion as one labelled figure (as `idbench render`, headless); "
      "returns it as a height × width × 3 uint8 array and writes it as PNG when png names a file");
}
