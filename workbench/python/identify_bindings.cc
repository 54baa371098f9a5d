// Identification from Python: the base parameters and the regressor of the
// joint-torque model, and idbench.identify (a log in, IdentifyResult out).
#include <cmath>
#include <optional>
#include <stdexcept>

#include "bindings.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/workbench/commands/identify_command.h"

namespace idbench::python {
namespace {

FrictionModel FrictionFor(const std::vector<std::string>& terms, double coulomb_smoothing, double coulomb_min_speed) {
  std::string why;
  std::optional<FrictionModel> friction = ParseFrictionTerms(terms, &why);
  if (!friction) throw std::invalid_argument("friction: " + why);
  friction->coulomb_smoothing = coulomb_smoothing;
  friction->coulomb_min_speed = coulomb_min_speed;
  if (!friction->IsValid(&why)) throw std::invalid_argument(why);
  return *friction;
}

// The identification's result as Python sees it: base parameters with their
// status (not identifiable: NaN, never a number), the physically consistent
// standard parameters, and the files `identify` writes, as text.
struct IdentifyResult {
  std::vector<std::string> base_names;
  Eigen::VectorXd beta, sigma, rel_sigma_percent, beta_model;
  Eigen::VectorXd sigma_white;  // σ as if the residual were white
  std::string sigma_method;     // how sigma was computed, with n_eff (SigmaMethodText)
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

// {status, fit_to_load, message, cause, cost_excess_percent, cost_tolerance_percent, bounds_at_optimum}.
py::dict VerdictDict(const JointTorqueIdentification& id) {
  const IdentificationVerdict& v = id.verdict;
  py::dict verdict;
  verdict["status"] = ToKey(v.status);
  verdict["fit_to_load"] = v.fit_to_load();
  verdict["message"] = v.message;
  verdict["cause"] = v.fit_to_load() ? py::object(py::none())
                                     : py::object(py::str(KeywordSpelling(v.cause)));
  verdict["cost_excess_percent"] = 100.0 * v.cost_excess;
  verdict["cost_tolerance_percent"] = 100.0 * v.cost_tolerance;
  py::list bounds;
  for (const ActiveBound& b : id.consistent.bounds_at_optimum) bounds.append(b.text);
  verdict["bounds_at_optimum"] = bounds;
  return verdict;
}

// The report as Python sees it (IdentifyResult).
IdentifyResult ToIdentifyResult(const RobotModel& model, const IdentifyOptions& options, const IdentifyReport& report) {
  const JointTorqueIdentification& id = report.identification;
  IdentifyResult r;
  r.base_names = id.base.names;
  r.beta = id.beta;
  r.sigma = id.linear.sigma;
  r.sigma_white = id.linear.sigma_white;
  r.sigma_method = SigmaMethodText(id.linear);
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
  r.verdict = VerdictDict(id);
  r.warnings = report.warnings;
  r.notes = report.notes;
  return r;
}

IdentifyResult Identify(const Robot& robot, const py::object& data, const IdentifyOptions& options,
                        const py::object& validate) {
  const RobotModel model = MountRobot(*robot.model, options.base_pose);  // gravity seen from the base
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (!options.format.IsValidFor(model.n_dof(), &why)) throw std::invalid_argument(why);
  if (!options.plausibility.IsValidFor(model, &why)) throw std::invalid_argument(why);
  // One log, or several of one robot identified together (a list).
  std::vector<PreparedLog> prepared;
  const std::vector<std::string> names = options.data_logs();
  if (py::isinstance<py::list>(data) || py::isinstance<py::tuple>(data)) {
    size_t k = 0;
    for (const py::handle item : data) {
      prepared.push_back(PrepareLogArgument(py::reinterpret_borrow<py::object>(item), names[k++], model,
                                            options.preparation(true)));
    }
  } else {
    prepared.push_back(PrepareLogArgument(data, options.data, model, options.preparation(true)));
  }
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
  return ToIdentifyResult(model, options, report);
}

// BaseParameters, base_parameters, standard_parameters, regressor.
void BindIdentificationModel(py::module_& m) {
  py::class_<BaseParameters>(m, "BaseParameters", "The identifiable combinations β = combination · π")
      .def_readonly("names", &BaseParameters::names)
      .def_readonly("independent", &BaseParameters::independent)
      .def_readonly("combination", &BaseParameters::combination)
      .def_property_readonly("n_base", &BaseParameters::n_base);

  const std::vector<std::string> default_friction = IdentifyOptions{}.friction;
  m.def(
      "base_parameters",
      [](const Robot& robot, const std::vector<std::string>& friction, double coulomb_smoothing,
         double coulomb_min_speed) {
        return ComputeBaseParameters(*robot.model, FrictionFor(friction, coulomb_smoothing, coulomb_min_speed));
      },
      py::arg("robot"), py::arg("friction") = default_friction, py::arg("coulomb_smoothing") = 0.0,
      py::arg("coulomb_min_speed") = 0.0,
      "The base parameters of the joint-torque model with these friction terms (as identify)");
  m.def(
      "standard_parameters",
      [](const Robot& robot, const std::vector<std::string>& friction, double coulomb_smoothing,
         double coulomb_min_speed) {
        const FrictionModel f = FrictionFor(friction, coulomb_smoothing, coulomb_min_speed);
        return py::make_tuple(StandardParameterNames(*robot.model, f), StandardParameters(*robot.model, f));
      },
      py::arg("robot"), py::arg("friction") = default_friction, py::arg("coulomb_smoothing") = 0.0,
      py::arg("coulomb_min_speed") = 0.0,
      "(names, values) of the robot file's standard parameters π");
  m.def(
      "regressor",
      [](const Robot& robot, const ArrayRef& q, const ArrayRef& qd, const ArrayRef& qdd,
         const std::vector<std::string>& friction, double coulomb_smoothing, double coulomb_min_speed,
         std::optional<BaseParameters> base) {
        const RobotModel& model = *robot.model;
        const FrictionModel f = FrictionFor(friction, coulomb_smoothing, coulomb_min_speed);
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
      py::arg("coulomb_smoothing") = 0.0, py::arg("coulomb_min_speed") = 0.0, py::arg("base") = py::none(),
      "The base regressor W stacked over the samples (n_samples × n_dof arrays in; rows sample·n_dof + joint), "
      "so that tau.reshape(-1) = W @ beta");
}

void BindIdentifyResult(py::module_& m) {
  py::class_<IdentifyResult>(m, "IdentifyResult")
      .def_readonly("base_names", &IdentifyResult::base_names)
      .def_readonly("beta", &IdentifyResult::beta, "Base parameters; NaN where not identifiable")
      .def_readonly("sigma", &IdentifyResult::sigma,
                    "Standard deviations from the residual as it is (batch means); inf where not identifiable")
      .def_readonly("sigma_white", &IdentifyResult::sigma_white, "Standard deviations as if the residual were white")
      .def_readonly("sigma_method", &IdentifyResult::sigma_method, "How sigma was computed, with n_eff")
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
}

}  // namespace

void BindIdentify(py::module_& m) {
  BindIdentificationModel(m);
  BindIdentifyResult(m);
  const IdentifyOptions id_defaults;
  m.def(
      "identify",
      [](const Robot& robot, const py::object& data, const std::string& estimator,
         const std::vector<std::string>& friction, double coulomb_smoothing, double coulomb_min_speed,
         const py::object& validate,
         const std::vector<std::string>& columns, const std::string& angle_unit,
         const std::vector<double>& drive_gains, const std::vector<double>& time_window,
         const std::vector<double>& validate_window, double max_gap,
         double filter_cutoff, int filter_order, int decimate, const std::vector<double>& mass_range,
         double total_mass, double total_mass_tolerance, const std::string& com_bound, double prior_weight,
         double cost_tolerance, bool write_unverified, const std::string& topic, const std::string& friction_side,
         const py::object& base_pose, const py::object& controller, const py::object& reference,
         bool torque_held) {
        IdentifyOptions options;
        options.friction_side = EnumArgument(kFrictionSideNames, friction_side);
        options.base_pose = BasePoseArgument(base_pose);
        options.format.transmission = robot.transmission;  // a log description's wins (IdentifyOptions::transmission)
        options.robot = robot.source;
        // A log's name in messages: its path, or "<data arrays>" (k-th of a list: "<data arrays k>").
        auto log_name = [](const py::handle& log, const std::string& arrays) {
          return py::isinstance<py::dict>(log) ? arrays : py::str(log).cast<std::string>();
        };
        if (py::isinstance<py::list>(data) || py::isinstance<py::tuple>(data)) {
          const py::sequence logs = data.cast<py::sequence>();
          if (logs.size() == 0) throw std::invalid_argument("data: expected a log, or a list of logs, got an empty list");
          options.data = log_name(logs[0], "<data arrays 1>");
          for (size_t k = 1; k < logs.size(); ++k) {
            options.more_data.push_back(log_name(logs[k], "<data arrays " + std::to_string(k + 1) + ">"));
          }
        } else {
          options.data = log_name(data, "<data arrays>");
        }
        options.controller = controller.is_none() ? "" : py::str(controller).cast<std::string>();
        options.reference = reference.is_none() ? "" : py::str(reference).cast<std::string>();
        options.format.torque_held = torque_held;
        options.validate = validate.is_none()                ? ""
                           : py::isinstance<py::dict>(validate) ? "<validate arrays>"
                                                                : py::str(validate).cast<std::string>();
        options.estimator = EnumArgument(kTorqueEstimatorNames, estimator);
        options.friction = friction;
        options.coulomb_smoothing = coulomb_smoothing;
        options.coulomb_min_speed = coulomb_min_speed;
        options.format.columns = columns;
        options.format.angle_unit = angle_unit;
        options.format.topic = topic;
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
      py::arg("robot"), py::arg("data"), py::kw_only(), py::arg("estimator") = std::string(ToString(id_defaults.estimator)),
      py::arg("friction") = id_defaults.friction, py::arg("coulomb_smoothing") = id_defaults.coulomb_smoothing,
      py::arg("coulomb_min_speed") = id_defaults.coulomb_min_speed,
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
      py::arg("topic") = std::string(), py::arg("friction_side") = std::string(kFrictionSideNames.Name(id_defaults.friction_side)),
      py::arg("base_pose") = py::none(), py::arg("controller") = py::none(), py::arg("reference") = py::none(),
      py::arg("torque_held") = false,
      "Identifies the robot from a joint log: a CSV path or a ROS 2 bag (a directory with metadata.yaml, a .db3 or "
      ".mcap file; topic= names its JointState topic when it has several), read as `idbench identify --data`, or a dict of arrays "
      "{t, q, [qd, qdd], tau} or with i (motor currents) for drive_gains (n_samples × n_dof, angles in angle_unit; "
      "without qd/qdd they are estimated by filtering); or a list of such logs of one robot, identified together "
      "(as several --data). estimator=\"iv\" or \"didim\" re-simulates the closed loop: controller= (a controller "
      "file) and reference= (a built-in motion or trajectory file) as `identify --controller --reference`; "
      "torque_held=True reads tau as the command held over each sample period (--torque-held). validate_window=(T0, T1) scores only that part of the held-out "
      "log. friction_side=\"actuator\" puts the friction and rotor terms on the motors, through the transmission of the "
      "data's log description or the robot's URDF; base_pose=(x, y, z, roll, pitch, yaw) mounts the robot (gravity "
      "along the world's -z). Options as `idbench identify`'s. The result's verdict says whether the physically consistent estimate is "
      "a robot model; urdf and joints_yaml are None when it is not (unless write_unverified=True).");
}

}  // namespace idbench::python
