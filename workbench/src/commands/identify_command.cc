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
#include "idbench/engine/urdf.h"
#include "idbench/workbench/formats/joint_log_csv.h"
#include "number_format.h"

namespace idbench {

bool WritesRobotModel(const IdentifyOptions& options, const IdentifyReport& report) {
  return report.identification.verdict.fit_to_load() || options.write_unverified;
}

std::string InFrontEndTerms(std::string text, OptionNames names) {
  const bool cli = names == OptionNames::kCommandLine;
  // Longest field names first: each is a prefix of none after it.
  const std::pair<const char*, std::string> fields[] = {
      {"plausibility.com_in_geometry = false", cli ? "--com-bound none" : "com_bound='none'"},
      {"plausibility.mass_factor_min, plausibility.mass_factor_max", cli ? "--mass-range" : "mass_range"},
      {"plausibility.total_mass_tolerance", cli ? "--total-mass-tolerance" : "total_mass_tolerance"},
      {"plausibility.total_mass", cli ? "--total-mass" : "total_mass"},
      {"plausibility.prior_weight", cli ? "--prior-weight" : "prior_weight"},
      {"plausibility.cost_tolerance", cli ? "--cost-tolerance" : "cost_tolerance"},
      {"write_unverified", cli ? "--write-unverified" : "write_unverified=True"},
  };
  for (const auto& [field, name] : fields) {
    for (size_t at = text.find(field); at != std::string::npos; at = text.find(field, at + name.size()))
      text.replace(at, std::string(field).size(), name);
  }
  return text;
}

std::string RefusedModelMessage(const IdentifyOptions& options, const IdentifyReport& report, OptionNames names) {
  const IdentificationVerdict& verdict = report.identification.verdict;
  if (verdict.fit_to_load()) return "";
  return InFrontEndTerms("the physically consistent estimate is not a robot model (" + verdict.message + "): " +
                             verdict.cause + ". identified.json holds the diagnostics; identified.urdf and joints.yaml " +
                             (options.write_unverified ? "are written anyway, as asked (write_unverified)"
                                                       : "are not written (write_unverified writes them anyway)"),
                         names);
}

double RelativeSigmaPercent(double value, double sigma) {
  if (!std::isfinite(value) || !std::isfinite(sigma) || !(std::abs(value) > 3.0 * sigma)) return std::nan("");
  return 100.0 * sigma / std::abs(value);
}

FrictionModel IdentifyOptions::friction_model() const {
  FrictionModel f = ParseFrictionTerms(friction, nullptr).value_or(FrictionModel{});
  f.coulomb_smoothing = coulomb_smoothing;
  return f;
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
  if (data.empty()) return fail("--data: a joint-log CSV is required");
  if (model == "per-body") {
    return fail("--model per-body: needs the wrench through every hinge, which a joint log does not carry; "
                "`idbench run` identifies per body from Bullet's joint feedback");
  }
  if (model != "torque") return fail("--model: expected 'torque' or 'per-body', got '" + model + "'");
  if (!ParseTorqueEstimator(estimator)) return fail("--estimator: expected ols, wls or pc, got '" + estimator + "'");
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("--friction: " + friction_why);
  if (!(coulomb_smoothing >= 0.0) || !std::isfinite(coulomb_smoothing))
    return fail("--coulomb-smoothing: must be >= 0 rad/s, got " + Shortest(coulomb_smoothing));
  std::string filter_why;
  if (!filter.IsValid(&filter_why)) return fail("--filter: " + filter_why);
  if (!preparation(true).IsValid(why)) return false;
  if (!validate_window.empty() && validate.empty()) return fail("validate_window: given without a held-out log (validate)");
  if (!preparation(false).IsValid(why)) return false;
  std::string plausibility_why;
  if (!plausibility.IsValid(&plausibility_why)) return fail(InFrontEndTerms(plausibility_why, OptionNames::kCommandLine));
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "--out", &out_why)) return fail(out_why);
  return true;
}

IdentifyReport RunIdentify(const RobotModel& model, const IdentifyOptions& options) {
  PreparedLog data = PrepareJointLog(options.data, model, options.preparation(true));
  std::optional<PreparedLog> held_out;
  std::optional<PreparedLog> held_out_whole;
  if (!options.validate.empty()) held_out = PrepareJointLog(options.validate, model, options.preparation(false));
  if (!options.validate.empty() && !options.validate_window.empty()) {
    IdentifyOptions whole = options;
    whole.validate_window.clear();
    held_out_whole = PrepareJointLog(options.validate, model, whole.preparation(false));
  }
  return IdentifyPreparedLogs(model, options, std::move(data), std::move(held_out), std::move(held_out_whole));
}

IdentifyReport IdentifyPreparedLogs(const RobotModel& model, const IdentifyOptions& options, PreparedLog data,
                                    std::optional<PreparedLog> held_out, std::optional<PreparedLog> held_out_whole) {
  IdentifyReport report;
  JointTorqueOptions id_options;
  id_options.friction = options.friction_model();
  id_options.estimator = *ParseTorqueEstimator(options.estimator);
  id_options.plausibility = options.plausibility;
  report.log = std::move(data.log);
  id_options.parallel_filter = data.parallel_filter;
  report.filtered = id_options.parallel_filter.has_value();
  report.parallel_filter = id_options.parallel_filter;
  report.derivatives = data.derivatives;
  report.notes = data.notes;
  report.warnings = data.warnings;
  try {
    report.identification = IdentifyJointTorque(model, report.log, id_options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(options.data + ": " + e.what());
  }
  if (held_out) {
    JointTorqueOptions held_options = id_options;
    held_options.parallel_filter = held_out->parallel_filter;
    for (std::string& note : held_out->notes) report.notes.push_back(std::move(note));
    for (std::string& warning : held_out->warnings) report.warnings.push_back(std::move(warning));
    try {
      report.validation = PredictTorques(model, held_options, report.identification.base,
                                         report.identification.beta, held_out->log);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(options.validate + ": " + e.what());
    }
    report.held_out_log = std::move(held_out->log);
    report.held_out_filter = held_out->parallel_filter;
    if (held_out_whole) {  // the whole file, beside the window
      held_options.parallel_filter = held_out_whole->parallel_filter;
      report.validation_whole_file = PredictTorques(model, held_options, report.identification.base,
                                                    report.identification.beta, held_out_whole->log);
    }
  }
  return report;
}

TorqueSeries PredictIdentifiedTorques(const RobotModel& model, const IdentifyOptions& options,
                                      const IdentifyReport& report, bool held_out) {
  JointTorqueOptions prediction;
  prediction.friction = options.friction_model();
  prediction.parallel_filter = held_out ? report.held_out_filter : report.parallel_filter;
  const JointTorqueIdentification& id = report.identification;
  if (held_out && !report.held_out_log) throw std::invalid_argument("no held-out log was identified with");
  return PredictTorqueSeries(model, prediction, id.base, id.beta, held_out ? *report.held_out_log : report.log);
}

std::string FormatIdentifyTables(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  const JointTorqueIdentification& id = report.identification;
  std::string out;
  for (const std::string& note : report.notes) out += note + "\n";
  char line[512];
  std::snprintf(line, sizeof(line), "Joint-torque identification of %s from %s: %d samples%s, %d base parameters, "
                "estimator %s, cond(W) = %.4g\n\n", model.name().c_str(), options.data.c_str(), report.log.n_samples(),
                report.filtered ? (" (" + report.derivatives + ")").c_str() : "", id.base.n_base(), options.estimator.c_str(),
                id.linear.cond);
  out += line;
  std::snprintf(line, sizeof(line), "%4s  %14s  %14s  %11s  %8s  %-10s  %s\n", "#", "robot file", "identified", "sigma",
                "%sigma", "status", "base parameter");
  out += line;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const ParameterStatus status = ClassifyParameter(id.beta[k], id.linear.sigma[k]);
    const char* name = id.base.names[static_cast<size_t>(k)].c_str();
    if (status == ParameterStatus::kNotIdentifiable) {
      std::snprintf(line, sizeof(line), "%4d  %14.6g  %14s  %11s  %8s  %-10s  %s\n", k + 1, id.beta_model[k], "-", "-",
                    "-", "not ident.", name);
    } else {
      std::snprintf(line, sizeof(line), "%4d  %14.6g  %14.6g  %11.3g  %8s  %-10s  %s\n", k + 1, id.beta_model[k],
                    id.beta[k], id.linear.sigma[k], Format("%.3g", RelativeSigmaPercent(id.beta[k], id.linear.sigma[k])).c_str(),
                    status == ParameterStatus::kIndistinguishableFromZero ? "~0" : ToString(status), name);
    }
    out += line;
  }
  out += "status: determined = sigma <= 10 % of the value; ~0 = |value| <= 3 sigma, indistinguishable from zero "
         "(%sigma '-': sigma itself is what is known)\n";
  if (options.estimator == "pc") {
    out += "sigma: of the least-squares estimate (the physically consistent one has no covariance of its own); "
           "%sigma: relative to the value shown\n";
  }
  if (id.linear.rank < id.base.n_base()) {
    const int n = id.base.n_base();
    const int missing = static_cast<int>(std::count(id.linear.identifiable.begin(), id.linear.identifiable.end(), false));
    std::snprintf(line, sizeof(line), "This log does not determine every base parameter: W has rank %d of %d (the "
                  "motion does not excite %d combinations); the %d parameters marked 'not ident.' take part in them "
                  "and get no value. The physically consistent fit keeps the robot file's values in those "
                  "directions.\n", id.linear.rank, n, n - id.linear.rank, missing);
    out += line;
  }
  auto joint_row = [&](const char* label, const Eigen::VectorXd& v) {
    out += label;
    for (int j = 0; j < v.size(); ++j) {
      std::snprintf(line, sizeof(line), "  %10.4g", v[j]);
      out += line;
    }
    out += '\n';
  };
  out += "\nTorque RMS per joint [N m]\n";
  joint_row("  fit       ", report.identification.fit.joint_rms);
  if (report.validation) joint_row("  validation", report.validation->joint_rms);
  std::string validation;
  if (report.validation) validation = ", validation " + Format("%.4g", report.validation->relative_error);
  if (report.validation_whole_file) {
    validation += " (validate_window " + Shortest(options.validate_window[0]) + "–" +
                  Shortest(options.validate_window[1]) + " s; whole file " +
                  Format("%.4g", report.validation_whole_file->relative_error) + ")";
  }
  std::snprintf(line, sizeof(line), "Relative torque error: fit %.4g%s\n", report.identification.fit.relative_error,
                validation.c_str());
  out += line;
  const PhysicallyConsistentFit& pc = id.consistent;
  std::snprintf(line, sizeof(line), "Physically consistent fit (SDP): cost %.6g vs OLS %.6g (the unconstrained "
                "optimum; +%.3g %%) and robot file %.6g; prior term %.3g; min pseudo-inertia eigenvalue %.3g; %s\n",
                pc.cost, pc.ols_cost, 100.0 * (pc.cost - pc.ols_cost) / pc.ols_cost, pc.start_cost, pc.prior_cost,
                pc.min_pseudo_inertia_eigenvalue.minCoeff(), pc.status.c_str());
  out += line;
  if (!pc.active_bounds.empty()) {
    out += "  on its bounds:";
    for (size_t k = 0; k < pc.active_bounds.size(); ++k) out += (k ? "; " : " ") + pc.active_bounds[k];
    out += '\n';
  }
  const PlausibleFitOptions bounds = MakePlausibleFitOptions(model, options.friction_model(), options.plausibility);
  for (int l = 0; l < model.n_links(); ++l) {
    const double outside = bounds.links[static_cast<size_t>(l)].com_outside_geometry;
    if (outside > 0.0) {
      out += "  no centre-of-mass bound on link '" + model.link(l).name + "': the file's centre of mass lies " +
             Format("%.3g", outside) + " m outside the box around its shapes\n";
    }
  }
  out += "Verdict: " + id.verdict.message + "\n";  // why, when refused: the command's one message
  return out;
}

namespace {

// Per joint, what a controller loads besides the URDF: the physically
// consistent estimate's friction, offset and rotor inertia (null when not in
// the model) and the drive gain the log was read with (null without currents).
struct JointDynamicsValues {
  std::string name;
  std::optional<double> viscous, coulomb, offset, rotor_inertia, drive_gain;
};
std::vector<JointDynamicsValues> JointDynamicsOf(const RobotModel& model, const IdentifyOptions& options,
                                                 const IdentifyReport& report) {
  const std::vector<std::string>& names = report.identification.standard_names;
  std::vector<JointDynamicsValues> joints(static_cast<size_t>(model.n_dof()));
  for (int j = 0; j < model.n_dof(); ++j) {
    JointDynamicsValues& v = joints[static_cast<size_t>(j)];
    v.name = model.link(j).joint_name;
    const std::string s = std::to_string(j + 1);
    for (size_t c = 0; c < names.size(); ++c) {
      const double value = report.identification.consistent.pi[static_cast<Eigen::Index>(c)];
      if (names[c] == "Fv" + s) v.viscous = value;
      if (names[c] == "Fc" + s) v.coulomb = value;
      if (names[c] == "offset" + s) v.offset = value;
      if (names[c] == "Ia" + s) v.rotor_inertia = value;
    }
    if (!options.format.drive_gains.empty()) v.drive_gain = options.format.drive_gains[static_cast<size_t>(j)];
  }
  return joints;
}

nlohmann::json JointDynamicsJson(const RobotModel& model, const IdentifyOptions& options, const IdentifyReport& report) {
  auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json joints = nlohmann::json::array();
  for (const JointDynamicsValues& v : JointDynamicsOf(model, options, report)) {
    joints.push_back({{"name", v.name}, {"viscous", value(v.viscous)}, {"coulomb", value(v.coulomb)},
                      {"offset", value(v.offset)}, {"rotor_inertia", value(v.rotor_inertia)},
                      {"drive_gain", value(v.drive_gain)}});
  }
  return joints;
}

}  // namespace

std::string FormatJointDynamicsYaml(const RobotModel& model, const IdentifyOptions& options,
                                    const IdentifyReport& report) {
  auto value = [](const std::optional<double>& v) { return v ? Shortest(*v) : std::string("null"); };
  std::string out = "# idbench identify: per-joint friction and drive values of the physically consistent estimate\n"
                    "# (the rigid-body parameters are in identified.urdf). Units: viscous [N m s/rad], coulomb and\n"
                    "# offset [N m], rotor_inertia [kg m^2], drive_gain [N m/A]; null: not in the model.\n"
                    "robot: \"" + model.name() + "\"\njoints:\n";
  for (const JointDynamicsValues& v : JointDynamicsOf(model, options, report)) {
    out += "  - name: \"" + v.name + "\"\n    viscous: " + value(v.viscous) + "\n    coulomb: " + value(v.coulomb) +
           "\n    offset: " + value(v.offset) + "\n    rotor_inertia: " + value(v.rotor_inertia) +
           "\n    drive_gain: " + value(v.drive_gain) + "\n";
  }
  return out;
}

std::string FormatIdentifiedJson(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  using nlohmann::json;
  const JointTorqueIdentification& id = report.identification;
  json base = json::array();
  for (int k = 0; k < id.base.n_base(); ++k) {
    const bool identifiable = id.linear.identifiable[static_cast<size_t>(k)];
    const json nothing;  // null: not identifiable from this log
    base.push_back({{"name", id.base.names[static_cast<size_t>(k)]},
                    {"value", identifiable ? json(id.beta[k]) : nothing},
                    {"sigma", identifiable ? json(id.linear.sigma[k]) : nothing},
                    {"rel_sigma_percent", identifiable && std::isfinite(RelativeSigmaPercent(id.beta[k], id.linear.sigma[k]))
                                              ? json(RelativeSigmaPercent(id.beta[k], id.linear.sigma[k]))
                                              : nothing},
                    {"variance_inflation", identifiable ? json(id.linear.variance_inflation[k]) : nothing},
                    {"status", ToString(ClassifyParameter(id.beta[k], id.linear.sigma[k]))},
                    {"robot_file_value", id.beta_model[k]}});
  }
  const Eigen::VectorXd pi_model = StandardParameters(model, options.friction_model());
  json standard = json::array();
  for (size_t c = 0; c < id.standard_names.size(); ++c) {
    const Eigen::Index k = static_cast<Eigen::Index>(c);
    standard.push_back({{"name", id.standard_names[c]}, {"value", id.consistent.pi[k]}, {"robot_file_value", pi_model[k]}});
  }
  // Per link: the plausible estimate's mass and centre of mass, and the
  // bounds it was held to.
  const PlausibleFitOptions bounds = MakePlausibleFitOptions(model, options.friction_model(), options.plausibility);
  json links = json::array();
  for (int l = 0; l < model.n_links(); ++l) {
    const Eigen::Index o = kInertialParametersPerLink * l;
    const double m = id.consistent.pi[o];
    const LinkPlausibilityBounds& b = bounds.links[static_cast<size_t>(l)];
    const Eigen::Vector3d c = id.consistent.pi.segment<3>(o + 1) / m;
    links.push_back({{"name", model.link(l).name},
                     {"mass", m},
                     {"robot_file_mass", model.link(l).inertia.mass},
                     {"mass_bounds", {b.mass_min, b.mass_max}},
                     {"com_B", {c.x(), c.y(), c.z()}},
                     {"com_box_B", b.bound_com ? json{{"min", {b.com_min_B.x(), b.com_min_B.y(), b.com_min_B.z()}},
                                                      {"max", {b.com_max_B.x(), b.com_max_B.y(), b.com_max_B.z()}}}
                                               : json(nullptr)},
                     {"com_bound", b.bound_com                       ? "geometry"
                                   : b.com_outside_geometry > 0.0    ? "none: the file's centre of mass lies outside the box around its shapes"
                                   : options.plausibility.com_in_geometry ? "none: the link has no shapes"
                                                                          : "none"},
                     {"com_outside_geometry", b.com_outside_geometry > 0.0 ? json(b.com_outside_geometry) : json(nullptr)}});
  }
  json unexcited = json::array();
  for (int c : id.base.unexcited) unexcited.push_back(id.standard_names[static_cast<size_t>(c)]);
  json bounds_at_optimum = json::array();
  for (const ActiveBound& b : id.consistent.bounds_at_optimum) {
    static const char* const kQuantity[] = {"mass", "com_x", "com_y", "com_z", "total_mass"};
    bounds_at_optimum.push_back({{"link", b.link >= 0 ? json(model.link(b.link).name) : json(nullptr)},
                                 {"joint", b.link >= 0 ? json(model.link(b.link).joint_name) : json(nullptr)},
                                 {"quantity", kQuantity[static_cast<int>(b.quantity)]},
                                 {"side", b.upper ? "upper" : "lower"},
                                 {"bound", b.bound},
                                 {"robot_file_value", b.file_value},
                                 {"text", b.text}});
  }
  const IdentificationVerdict& v = id.verdict;
  const json verdict = {
      {"status", ToKey(v.status)},
      {"fit_to_load", v.fit_to_load()},
      {"message", v.message},
      {"cause", v.fit_to_load() ? json(nullptr) : json(InFrontEndTerms(v.cause, OptionNames::kCommandLine))},
      {"converged", id.consistent.converged},
      {"cost_excess_percent", 100.0 * v.cost_excess},
      {"cost_tolerance_percent", 100.0 * v.cost_tolerance},
      {"bounds_at_optimum", bounds_at_optimum},
      {"robot_model_written", WritesRobotModel(options, report)},
      {"write_unverified", options.write_unverified}};
  json result = {
      {"command", options.command_line},
      {"verdict", verdict},
      {"robot", model.name()},
      {"data", options.data},
      {"n_samples", report.log.n_samples()},
      {"derivatives", report.filtered ? "estimated: zero-phase Butterworth + central differences (" + report.derivatives + ")"
                                      : "from the log"},
      {"log_preparation", report.notes},
      {"time_window", options.time_window.empty() ? json(nullptr) : json(options.time_window)},
      {"model", options.model},
      {"estimator", options.estimator},
      {"friction", options.friction},
      {"cond", std::isfinite(id.linear.cond) ? json(id.linear.cond) : json(nullptr)},
      {"rank", id.linear.rank},
      {"base_parameters", base},
      {"unexcited_standard_parameters", unexcited},
      {"fit", {{"joint_rms", ToStdVector(report.identification.fit.joint_rms)}, {"relative_error", report.identification.fit.relative_error}}},
      {"robot_file_fit",
       {{"joint_rms", ToStdVector(report.identification.model_fit.joint_rms)}, {"relative_error", report.identification.model_fit.relative_error}}},
      {"physically_consistent",
       {{"cost", id.consistent.cost},
        {"ols_cost", id.consistent.ols_cost},
        {"start_cost", id.consistent.start_cost},
        {"min_pseudo_inertia_eigenvalue", ToStdVector(id.consistent.min_pseudo_inertia_eigenvalue)},
        {"prior_cost", id.consistent.prior_cost},
        {"duality_gap", id.consistent.duality_gap},
        {"converged", id.consistent.converged},
        {"status", id.consistent.status},
        {"iterations", id.consistent.evaluations},
        {"active_bounds", id.consistent.active_bounds},
        {"settings",
         {{"mass_range", {options.plausibility.mass_factor_min, options.plausibility.mass_factor_max}},
          {"total_mass", options.plausibility.total_mass > 0.0 ? json(options.plausibility.total_mass) : json(nullptr)},
          {"total_mass_tolerance", options.plausibility.total_mass_tolerance},
          {"com_bound", options.plausibility.com_in_geometry ? "geometry" : "none"},
          {"prior_weight", options.plausibility.prior_weight},
          {"cost_tolerance", options.plausibility.cost_tolerance}}},
        {"standard_parameters", standard},
        {"links", links}}},
      {"joints", JointDynamicsJson(model, options, report)},
  };
  if (report.validation) {
    result["validation"] = {{"data", options.validate},
                            {"joint_rms", ToStdVector(report.validation->joint_rms)},
                            {"relative_error", report.validation->relative_error}};
    if (report.validation_whole_file) {
      result["validation"]["window"] = options.validate_window;
      result["validation"]["whole_file"] = {{"joint_rms", ToStdVector(report.validation_whole_file->joint_rms)},
                                            {"relative_error", report.validation_whole_file->relative_error}};
    }
  }
  return result.dump(2) + "\n";
}

std::string FormatIdentifiedUrdf(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  return WriteUrdf(ModelWithStandardParameters(model, options.friction_model(), report.identification.consistent.pi));
}

}  // namespace idbench
