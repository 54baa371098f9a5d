#include "idbench/workbench/commands/payload_command.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/urdf.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "number_format.h"
#include "formats/json_number.h"
#include "formats/sigma_method_json.h"

namespace idbench {
namespace {

// The estimator's view of a prepared log.
TorqueLog ToTorqueLog(PreparedLog prepared) {
  TorqueLog out;
  out.motion = std::move(prepared.log);
  out.parallel_filter = prepared.parallel_filter;
  return out;
}

// JSON number, or null where not finite (not determined).
nlohmann::json NumbersOrNull(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index k = 0; k < v.size(); ++k) out.push_back(NumberOrNull(v[k]));
  return out;
}

// The index of the link named `name` in the chain, or -1.
int FindLink(const RobotModel& model, const std::string& name) {
  for (int k = 0; k < model.n_links(); ++k) {
    if (model.links()[static_cast<size_t>(k)].name == name) return k;
  }
  return -1;
}

// %.17g: the written file reads back to the same doubles.
std::string Exact(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

}  // namespace

FrictionModel PayloadOptions::friction_model() const {
  FrictionModel f = ParseFrictionTerms(friction, nullptr).value_or(FrictionModel{});
  f.coulomb_smoothing = coulomb_smoothing;
  f.coulomb_min_speed = coulomb_min_speed;
  return f;
}

LogPreparationOptions PayloadOptions::preparation(bool unloaded) const {
  LogPreparationOptions out;
  out.format = format;
  out.time_window = unloaded ? unloaded_time_window : time_window;
  out.window_field = unloaded ? "unloaded_time_window" : "time_window";
  out.filter = filter;
  out.max_gap_s = max_gap_s;
  return out;
}

bool PayloadOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (robot.empty()) return fail("robot: the identified robot (URDF) is required");
  if (loaded_log.empty()) return fail("loaded_log: the log with the payload is required");
  // The same file however spelled (device and inode), and the same part of it:
  // one recording cannot be both (two windows of one file can).
  if (!unloaded_log.empty() && IsSameFile(unloaded_log, loaded_log) && unloaded_time_window == time_window)
    return fail("unloaded_log: expected a log without the payload, got '" + unloaded_log + "', the loaded log '" +
                loaded_log + "' again" + (unloaded_log == loaded_log ? "" : " (the same file)"));
  if (!unloaded_time_window.empty() && unloaded_log.empty())
    return fail("unloaded_time_window: given without an unloaded log (unloaded_log)");
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  const FrictionModel coulomb{.coulomb_smoothing = coulomb_smoothing, .coulomb_min_speed = coulomb_min_speed};
  if (std::string coulomb_why; !coulomb.IsValid(&coulomb_why)) return fail(coulomb_why);
  if (!(max_relative_sigma > 0.0) || !std::isfinite(max_relative_sigma))
    return fail("max_relative_sigma: expected a fraction > 0, got " + Shortest(max_relative_sigma));
  if (!(max_projection_distance > 0.0) || !std::isfinite(max_projection_distance))
    return fail("max_projection_distance: expected a number of sigma > 0, got " + Shortest(max_projection_distance));
  if (!base_pose.IsValid(why)) return false;
  if (!preparation(false).IsValid(why) || !preparation(true).IsValid(why)) return false;
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

bool PayloadOptions::IsValidFor(const RobotModel& model, std::string* why) const {
  if (!format.IsValidFor(model.n_dof(), why)) return false;
  if (!IsMountedAt(model, base_pose)) {
    if (why) *why = "base_pose: the model's gravity is not the world's -z seen from this base; mount the model (MountRobot)";
    return false;
  }
  if (payload_link.empty() || FindLink(model, payload_link) >= 0) return true;
  std::string names;
  for (const Link& link : model.links()) names += (names.empty() ? "'" : ", '") + link.name + "'";
  if (why) {
    *why = "payload_link: robot '" + model.name() + "' has no link '" + payload_link + "' in its chain (links: " +
           names + ")";
  }
  return false;
}

PayloadEstimatorOptions PayloadOptions::estimator(const RobotModel& model) const {
  PayloadEstimatorOptions out;
  out.link = payload_link.empty() ? model.n_links() - 1 : FindLink(model, payload_link);
  out.friction = friction_model();
  out.max_relative_sigma = max_relative_sigma;
  out.max_projection_distance = max_projection_distance;
  return out;
}

std::string PayloadSummary::BriefReport() const {
  char text[512];
  const PayloadBody& b = estimate.body;
  std::snprintf(text, sizeof(text), "payload on link '%s': mass %.5g kg, com [%.4g, %.4g, %.4g] m (%s)%s%s",
                link_name.c_str(), b.mass, b.p_BoPcm_B.x(), b.p_BoPcm_B.y(), b.p_BoPcm_B.z(),
                PayloadStatusName(status), message.empty() ? "" : ": ", message.c_str());
  return text;
}

PayloadSummary RunPayload(const RobotModel& model, const PayloadOptions& options) {
  std::string why;
  if (!options.IsValidFor(model, &why)) throw std::invalid_argument(why);
  PreparedLog loaded = PrepareJointLog(options.loaded_log, model, options.preparation(false));
  std::optional<PreparedLog> unloaded;
  if (!options.unloaded_log.empty()) unloaded = PrepareJointLog(options.unloaded_log, model, options.preparation(true));
  return RunPayloadOnLogs(model, options, std::move(loaded), std::move(unloaded));
}

PayloadSummary RunPayloadOnLogs(const RobotModel& model, const PayloadOptions& options, PreparedLog loaded,
                                std::optional<PreparedLog> unloaded) {
  std::string why;
  if (!options.IsValidFor(model, &why)) throw std::invalid_argument(why);
  PayloadSummary summary;
  const PayloadEstimatorOptions estimator = options.estimator(model);
  summary.link_name = model.links()[static_cast<size_t>(estimator.link)].name;
  for (PreparedLog* log : {&loaded, unloaded ? &*unloaded : nullptr}) {
    if (!log) continue;
    for (std::string& note : log->notes) summary.notes.push_back(std::move(note));
    for (std::string& warning : log->warnings) summary.warnings.push_back(std::move(warning));
    // The estimate takes the log as held: beyond LogPreparationOptions::
    // kMaxHeldSamples, every log_stride-th sample. Said, not hidden.
    if (log->log_stride > 1) {
      const std::string& path = log == &loaded ? options.loaded_log : options.unloaded_log;
      summary.notes.push_back(path + ": " + std::to_string(log->n_samples) + " prepared samples, one in " +
                              std::to_string(log->log_stride) + " (" + std::to_string(log->log.n_samples()) +
                              ") used for the payload fit (at most " +
                              std::to_string(LogPreparationOptions::kMaxHeldSamples) +
                              " held; a time window chooses which part of the log)");
    }
  }
  summary.n_loaded = loaded.log.n_samples();
  summary.n_unloaded = unloaded ? unloaded->log.n_samples() : 0;
  // Estimate.
  const TorqueLog loaded_log = ToTorqueLog(std::move(loaded));
  std::optional<TorqueLog> unloaded_log;
  if (unloaded) unloaded_log = ToTorqueLog(std::move(*unloaded));
  summary.estimate = EstimatePayload(model, loaded_log, unloaded_log ? &*unloaded_log : nullptr, estimator);
  summary.status = summary.estimate.status;
  summary.message = summary.estimate.message;
  return summary;
}

bool WritesPayloadUrdf(const PayloadOptions& options, const PayloadSummary& summary) {
  if (summary.good()) return true;
  return options.write_unverified && summary.status != PayloadStatus::kNotIdentifiable;
}

std::string FormatPayloadTable(const PayloadOptions& options, const PayloadSummary& summary) {
  const PayloadEstimate& e = summary.estimate;
  std::string out;
  for (const std::string& note : summary.notes) out += note + "\n";
  char line[512];
  std::snprintf(line, sizeof(line), "Payload on link '%s' from %s (%d samples)%s%s%s: rank %d, residual RMS %.3g N m, "
                "payload torque / residual %.3g\n\n", summary.link_name.c_str(), options.loaded_log.c_str(),
                summary.n_loaded, e.two_logs ? " and the unloaded " : ", the robot file's model subtracted",
                e.two_logs ? options.unloaded_log.c_str() : "",
                e.two_logs ? (" (" + std::to_string(summary.n_unloaded) + " samples)").c_str() : "", e.rank,
                e.residual_rms, e.payload_signal_to_noise);
  out += line;
  std::snprintf(line, sizeof(line), "%-6s  %14s  %11s  %-6s\n", "", "estimate", "sigma", "unit");
  out += line;
  const Eigen::Matrix<double, 10, 1> q = PayloadQuantities(e.body);
  for (int k = 0; k < 10; ++k) {
    const char* unit = k == 0 ? "kg" : k < 4 ? "m" : "kg m2";
    if (!e.identifiable[static_cast<size_t>(k)]) {
      std::snprintf(line, sizeof(line), "%-6s  %14s  %11s  %-6s\n", PayloadQuantityNames()[k].c_str(), "not ident.",
                    "-", unit);
    } else {
      std::snprintf(line, sizeof(line), "%-6s  %14.6g  %11.3g  %-6s\n", PayloadQuantityNames()[k].c_str(), q[k],
                    e.sigma[k], unit);
    }
    out += line;
  }
  out += "(centre of mass in link '" + summary.link_name + "' frame; inertia about the centre of mass, in its axes)\n";
  out += SigmaMethodText(e.covariance_method, "payload.json") + "\n";
  for (int k = 0; k < 10; ++k) {
    if (!e.identifiable[static_cast<size_t>(k)]) out += PayloadQuantityNames()[k] + ": " + e.not_identifiable_reason[k] + "\n";
  }
  if (e.projection_distance > 0.0) {
    std::snprintf(line, sizeof(line), "The least-squares payload is not a physical body; the nearest is %.3g sigma "
                  "from it (shown above)\n", e.projection_distance);
    out += line;
  }
  out += std::string("Verdict: ") + PayloadStatusName(summary.status) + (summary.message.empty() ? "" : ": ") +
         summary.message + "\n";
  return out;
}

std::string FormatPayloadJson(const RobotModel& model, const PayloadOptions& options, const PayloadSummary& summary) {
  using nlohmann::json;
  const PayloadEstimate& e = summary.estimate;
  const Eigen::Matrix<double, 10, 1> q = PayloadQuantities(e.body);
  Eigen::Matrix<double, 10, 1> shown = q;
  for (int k = 0; k < 10; ++k) {
    if (!e.identifiable[static_cast<size_t>(k)]) shown[k] = std::nan("");
  }
  json not_identifiable = json::array();
  for (int k = 0; k < 10; ++k) {
    if (!e.identifiable[static_cast<size_t>(k)])
      not_identifiable.push_back({{"name", PayloadQuantityNames()[k]}, {"reason", e.not_identifiable_reason[k]}});
  }
  json least_squares = json::object();
  for (int i = 0; i < 10; ++i) least_squares[PayloadInertialParameterNames()[i]] = NumberOrNull(e.phi[i]);
  const json result = {
      {"mass", NumberOrNull(shown[0])},
      {"com", NumbersOrNull(shown.segment<3>(1))},
      {"inertia", NumbersOrNull(shown.tail<6>())},
      {"sigma", {{"mass", NumberOrNull(e.sigma[0])},
                 {"com", NumbersOrNull(e.sigma.segment<3>(1))},
                 {"inertia", NumbersOrNull(e.sigma.tail<6>())}}},
      {"sigma_white", {{"mass", NumberOrNull(e.sigma_white[0])},
                       {"com", NumbersOrNull(e.sigma_white.segment<3>(1))},
                       {"inertia", NumbersOrNull(e.sigma_white.tail<6>())}}},
      {"sigma_method", SigmaMethodJson(e.covariance_method, "payload.json")},
      {"verdict", {{"status", PayloadStatusName(summary.status)},
                   {"good", summary.good()},
                   {"message", summary.message},
                   {"urdf_written", WritesPayloadUrdf(options, summary)},
                   {"write_unverified", options.write_unverified}}},
      {"not_identifiable", not_identifiable},
      {"link", summary.link_name},
      {"frames", "com in the link's frame [m]; inertia [kg m2] about the centre of mass, link axes: Ixx, Ixy, Ixz, "
                 "Iyy, Iyz, Izz"},
      {"robot", model.name()},
      {"base_pose", options.base_pose.xyz_rpy},
      {"command", options.command_line},
      {"method", e.two_logs ? "loaded and unloaded logs (the robot's base parameters estimated from both)"
                            : "loaded log, the robot file's model subtracted"},
      {"loaded", {{"data", options.loaded_log}, {"n_samples", summary.n_loaded},
                  {"time_window", options.time_window.empty() ? json(nullptr) : json(options.time_window)}}},
      {"unloaded", e.two_logs ? json{{"data", options.unloaded_log}, {"n_samples", summary.n_unloaded},
                                     {"time_window", options.unloaded_time_window.empty()
                                                         ? json(nullptr) : json(options.unloaded_time_window)}}
                              : json(nullptr)},
      {"least_squares_first_moment_and_inertia_about_link_origin", least_squares},
      {"projection_distance_sigma", e.projection_distance},
      {"min_pseudo_inertia_eigenvalue", e.min_pseudo_inertia_eigenvalue},
      {"rank", e.rank},
      {"n_equations", e.n_equations},
      {"residual_rms", e.residual_rms},
      {"payload_signal_to_noise", NumberOrNull(e.payload_signal_to_noise)},
      {"friction", e.two_logs ? json(options.friction) : json(nullptr)},
      {"log_preparation", summary.notes},
  };
  return result.dump(2) + "\n";
}

std::string FormatPayloadUrdf(const RobotModel& model, const PayloadOptions& options, const PayloadSummary& summary) {
  const PayloadBody& b = summary.estimate.body;
  const std::string link = EscapeXml(summary.link_name);
  std::string out = "<!-- Payload identified by idbench (" + EscapeXml(options.command_line) + ") for robot '" +
                    EscapeXml(model.name()) + "', verdict: " + PayloadStatusName(summary.status) +
                    ". Paste inside <robot>. -->\n";
  out += "<joint name=\"" + link + "_payload_joint\" type=\"fixed\">\n  <parent link=\"" + link +
         "\"/>\n  <child link=\"" + link + "_payload\"/>\n  <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n</joint>\n";
  const auto& I = b.I_Pcm_B;
  out += "<link name=\"" + link + "_payload\">\n  <inertial>\n    <origin xyz=\"" + Exact(b.p_BoPcm_B.x()) + " " +
         Exact(b.p_BoPcm_B.y()) + " " + Exact(b.p_BoPcm_B.z()) + "\" rpy=\"0 0 0\"/>\n    <mass value=\"" +
         Exact(b.mass) + "\"/>\n    <inertia ixx=\"" + Exact(I[0]) + "\" ixy=\"" + Exact(I[1]) + "\" ixz=\"" +
         Exact(I[2]) + "\" iyy=\"" + Exact(I[3]) + "\" iyz=\"" + Exact(I[4]) + "\" izz=\"" + Exact(I[5]) +
         "\"/>\n  </inertial>\n</link>\n";
  return out;
}

std::vector<std::pair<std::filesystem::path, std::string>> PayloadFiles(const RobotModel& model,
                                                                       const PayloadOptions& options,
                                                                       const PayloadSummary& summary) {
  const std::filesystem::path dir(options.out_dir);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "payload.json", FormatPayloadJson(model, options, summary)}};
  if (WritesPayloadUrdf(options, summary))
    files.emplace_back(dir / "payload.urdf.xml", FormatPayloadUrdf(model, options, summary));
  return files;
}

}  // namespace idbench
