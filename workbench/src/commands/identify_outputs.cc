// The files `identify` writes: identified.json, joints.yaml, identified.urdf, identified.xml.
#include "idbench/workbench/commands/identify_command.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "idbench/engine/urdf.h"
#include "idbench/workbench/commands/export_command.h"
#include "idbench/workbench/formats/joints_yaml.h"
#include "idbench/workbench/formats/mjcf_writer.h"
#include "formats/sigma_method_json.h"
#include "number_format.h"

namespace idbench {

namespace {

// Per joint, what a controller loads besides the URDF: the physically
// consistent estimate's friction, offset and rotor inertia (null when not in
// the model) and the drive gain the log was read with (null without currents).
// Actuator side (friction_side kActuator): a joint one motor k drives alone
// with ratio N (Transmission::SingleMotorOf) gets motor k's terms as their
// joint-side equivalents by virtual work, Fv·N², Fc·|N|, offset·N, Ia·N²; a
// coupled joint has none (null, never 0) and lists the motors turning with it.
std::vector<JointDynamicsValues> JointDynamicsOf(const RobotModel& model, const IdentifyOptions& options,
                                                 const IdentifyReport& report) {
  const std::vector<std::string>& names = report.identification.standard_names;
  const FrictionModel friction = options.friction_model();
  // The standard parameter named `term` + the joint's (or its motor's) number.
  auto parameter = [&](const std::string& term, const std::string& number) -> std::optional<double> {
    for (size_t c = 0; c < names.size(); ++c) {
      if (names[c] == term + number) return report.identification.consistent.pi[static_cast<Eigen::Index>(c)];
    }
    return std::nullopt;
  };
  auto scaled = [](const std::optional<double>& v, double factor) {
    return v ? std::optional<double>(*v * factor) : std::nullopt;
  };
  std::vector<JointDynamicsValues> joints(static_cast<size_t>(model.n_dof()));
  for (int j = 0; j < model.n_dof(); ++j) {
    JointDynamicsValues& v = joints[static_cast<size_t>(j)];
    v.name = model.link(j).joint_name;
    if (!options.format.drive_gains.empty()) v.drive_gain = options.format.drive_gains[static_cast<size_t>(j)];
    if (!friction.actuator_side()) {
      const std::string s = std::to_string(j + 1);
      v.viscous = parameter("Fv", s);
      v.coulomb = parameter("Fc", s);
      v.offset = parameter("offset", s);
      v.rotor_inertia = parameter("Ia", s);
      continue;
    }
    const std::optional<Transmission::SingleMotor> single = SingleMotorOf(friction, j);
    if (!single) {
      for (int k = 0; k < model.n_dof(); ++k) {
        if (friction.actuator_from_joint(k, j) != 0.0) v.coupled_motors.push_back(k);
      }
      continue;
    }
    const std::string m = "m" + std::to_string(single->motor + 1);
    const double N = single->ratio;
    v.viscous = scaled(parameter("Fv", m), N * N);
    v.coulomb = scaled(parameter("Fc", m), std::abs(N));
    v.offset = scaled(parameter("offset", m), N);
    v.rotor_inertia = scaled(parameter("Ia", m), N * N);
  }
  return joints;
}

// Actuator-side terms as joint-side equivalents (Ia·N², Fv·N², Fc·|N|) per
// joint a motor drives alone (null for a coupled joint, or a term not in
// the model), from the physically consistent estimate.
nlohmann::json JointSideEquivalentsJson(const RobotModel& model, const IdentifyOptions& options,
                                        const IdentifyReport& report) {
  auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json Ia = nlohmann::json::array(), Fv = Ia, Fc = Ia;
  for (const JointDynamicsValues& v : JointDynamicsOf(model, options, report)) {
    Ia.push_back(value(v.rotor_inertia));
    Fv.push_back(value(v.viscous));
    Fc.push_back(value(v.coulomb));
  }
  return {{"Ia", Ia}, {"Fv", Fv}, {"Fc", Fc}};
}

}  // namespace

std::string FormatJointDynamicsYaml(const RobotModel& model, const IdentifyOptions& options,
                                    const IdentifyReport& report) {
  return FormatIdentifiedModel(ExportFormat::kYaml, model, options.friction_model(), report.identification.consistent.pi,
                               JointDynamicsOf(model, options, report));
}

std::string FormatIdentifiedJson(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  using nlohmann::json;
  const JointTorqueIdentification& id = report.identification;
  json base = json::array();
  for (int k = 0; k < id.base.n_base(); ++k) {
    const bool identifiable = id.linear.identifiable[static_cast<size_t>(k)];
    const json nothing;  // null: not identifiable from this log
    // β_k = Σ coefficient · standard parameter (its row of the combination
    // matrix; exact zeros left out), the leading term first: a published
    // table (FIGAROH's, BIRDy's) matched row by row.
    json combination = json::array();
    const int lead = id.base.independent[static_cast<size_t>(k)];
    combination.push_back({{"parameter", id.standard_names[static_cast<size_t>(lead)]},
                           {"coefficient", id.base.combination(k, lead)}});
    for (Eigen::Index c = 0; c < id.base.combination.cols(); ++c) {
      if (c == lead || id.base.combination(k, c) == 0.0) continue;
      combination.push_back({{"parameter", id.standard_names[static_cast<size_t>(c)]},
                             {"coefficient", id.base.combination(k, c)}});
    }
    base.push_back({{"name", id.base.names[static_cast<size_t>(k)]},
                    {"combination", combination},
                    {"value", identifiable ? json(id.beta[k]) : nothing},
                    {"sigma", identifiable ? json(id.linear.sigma[k]) : nothing},
                    {"sigma_white", identifiable ? json(id.linear.sigma_white[k]) : nothing},
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
      {"cause", v.fit_to_load() ? json(nullptr) : json(v.cause)},
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
      {"data_files", options.data_logs()},
      {"n_samples", report.n_samples},
      {"n_samples_read", report.n_samples_read},
      {"derivatives", report.filtered ? "estimated: zero-phase Butterworth + central differences (" + report.derivatives + ")"
                                      : "from the log"},
      {"log_preparation", report.notes},
      {"time_window", options.time_window.empty() ? json(nullptr) : json(options.time_window)},
      {"model", std::string(kIdentificationModelNames.Name(options.model))},
      {"estimator", std::string(ToString(options.estimator))},
      {"solve",
       {{"iterations", id.linear.solve.iterations},
        {"converged", id.linear.solve.converged},
        {"message", id.linear.solve.message}}},
      {"friction", options.friction},
      {"cond", std::isfinite(id.linear.cond) ? json(id.linear.cond) : json(nullptr)},
      {"rank", id.linear.rank},
      {"sigma_method", SigmaMethodJson(id.linear.covariance_method, "identified.json")},
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
      {"joints", JointDynamicsJson(JointDynamicsOf(model, options, report))},
  };
  if (report.closed_loop) {
    // The closed-loop estimator's verdict; sigma_method above is its last iteration's.
    result["closed_loop"] = {{"controller", options.controller},
                             {"reference", options.reference},
                             {"iterations", report.closed_loop->iterations},
                             {"converged", report.closed_loop->converged},
                             {"last_change", report.closed_loop->last_change},
                             {"message", report.closed_loop->message}};
  }
  if (options.friction_side == FrictionSide::kActuator) {
    result["joint_side"] = JointSideEquivalentsJson(model, options, report);
    // The transmission the actuator-side terms act through (a log
    // description's or the URDF's): export reads it back from here.
    const Eigen::MatrixXd A = options.friction_model().actuator_from_joint;
    json rows = json::array();
    for (Eigen::Index k = 0; k < A.rows(); ++k) rows.push_back(ToStdVector(A.row(k).transpose()));
    const std::optional<Transmission> used = options.transmission();
    result["transmission"] = {{"actuator_from_joint", rows}, {"source", used ? json(used->source) : json(nullptr)}};
  }
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
  if (!report.parts.empty()) {  // several logs stacked: each one's samples and cond(W) alone
    json logs = json::array();
    for (const IdentifiedLogPart& p : report.parts) {
      logs.push_back({{"path", p.path}, {"n_samples", p.n_samples}, {"n_samples_read", p.n_samples_read},
                      {"cond", std::isfinite(p.cond) ? json(p.cond) : json(nullptr)}});
    }
    result["data_logs"] = logs;
  }
  return result.dump(2) + "\n";
}

std::string FormatIdentifiedUrdf(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  return FormatIdentifiedModel(ExportFormat::kUrdf, model, options.friction_model(), report.identification.consistent.pi,
                               JointDynamicsOf(model, options, report));
}

std::string FormatIdentifiedMjcf(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  return FormatIdentifiedModel(ExportFormat::kMjcf, model, options.friction_model(), report.identification.consistent.pi,
                               JointDynamicsOf(model, options, report));
}

}  // namespace idbench
