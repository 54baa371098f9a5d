#include "idbench/workbench/commands/gains_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "number_format.h"
#include "formats/json_number.h"
#include "formats/sigma_method_json.h"

namespace idbench {
namespace {

// A log's motion and currents for the estimator.
CurrentLog ToCurrentLog(PreparedLog prepared) {
  CurrentLog out;
  out.current = std::move(prepared.log.tau);
  out.motion = std::move(prepared.log);
  out.parallel_filter = prepared.parallel_filter;
  return out;
}

// JSON number, or null where not finite (not determined).

// "Drive gains of <robot> from <data> (unloaded, N samples) and ...: U unknowns, rank R".
std::string Headline(const GainsReport& report) {
  char line[512];
  std::snprintf(line, sizeof(line), "Drive gains of %s from %s (unloaded, %d samples) and %s (payload %g kg, %d "
                "samples): %d unknowns, rank %d", report.robot.c_str(), report.data.c_str(), report.n_unloaded,
                report.loaded.c_str(), report.payload_mass, report.n_loaded,
                static_cast<int>(report.estimate.unknown_names.size()), report.estimate.rank);
  return line;
}

std::string ResidualLine(const DriveGainEstimate& e) {
  char line[128];
  std::snprintf(line, sizeof(line), "Relative torque residual: unloaded %.4g, loaded %.4g", e.unloaded_relative_error,
                e.loaded_relative_error);
  return line;
}

}  // namespace

std::string GainsReport::BriefReport() const {
  const DriveGainEstimate& e = estimate;
  std::string gains;
  double worst = -1.0;  // largest %σ over the determined gains
  int worst_joint = 0;
  for (Eigen::Index j = 0; j < e.gains.size(); ++j) {
    gains += (j > 0 ? ", " : "") + (std::isfinite(e.gains[j]) ? Format("%.6g", e.gains[j]) : std::string("not ident."));
    const double percent = 100.0 * e.sigma[j] / std::abs(e.gains[j]);
    if (std::isfinite(e.gains[j]) && percent > worst) worst = percent, worst_joint = static_cast<int>(j) + 1;
  }
  std::string out = Headline(*this) + "\nK [N m/A]: " + gains;
  if (worst >= 0.0) out += " (largest %sigma " + Format("%.3g", worst) + ", joint " + std::to_string(worst_joint) + ")";
  out += "\n" + ResidualLine(e) + "\n" + std::string(kDriveGainStatusNames.Name(e.status));
  if (!e.message.empty()) out += ": " + e.message;
  return out + "\n";
}

FrictionModel GainsOptions::friction_model() const {
  FrictionModel f = ParseFrictionTerms(friction, nullptr).value_or(FrictionModel{});
  f.coulomb_smoothing = coulomb_smoothing;
  f.coulomb_min_speed = coulomb_min_speed;
  return f;
}

LogPreparationOptions GainsOptions::preparation(bool loaded_log) const {
  LogPreparationOptions out;
  out.format = format;
  out.time_window = loaded_log ? loaded_time_window : time_window;
  out.window_field = loaded_log ? "loaded_time_window" : "time_window";
  out.torques = TorqueColumns::kCurrents;
  out.filter = filter;
  out.max_gap_s = max_gap_s;
  // EstimateDriveGains takes the prepared logs whole (not streamed): a log
  // is held whole, and one longer than the bound is refused before it is.
  out.max_held_samples = 0;
  out.max_samples = LogPreparationOptions::kMaxHeldSamples;
  return out;
}

bool GainsOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (data.empty()) return fail("data: the unloaded log is required");
  if (loaded.empty()) return fail("loaded: the log with the payload is required");
  // The same file however spelled (device and inode), and the same part of it.
  if (IsSameFile(loaded, data) && loaded_time_window == time_window)
    return fail("loaded: expected the log with the payload, got '" + loaded + "', the unloaded log '" + data +
                "' again" + (loaded == data ? "" : " (the same file)"));
  DriveGainOptions gains;
  gains.payload_mass = payload_mass;
  std::string gains_why;
  if (!gains.IsValid(&gains_why)) return fail("payload_mass: " + gains_why);
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  const FrictionModel coulomb{.coulomb_smoothing = coulomb_smoothing, .coulomb_min_speed = coulomb_min_speed};
  if (std::string coulomb_why; !coulomb.IsValid(&coulomb_why)) return fail(coulomb_why);
  if (!preparation(false).IsValid(why) || !preparation(true).IsValid(why)) return false;
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

GainsReport RunGains(const RobotModel& model, const GainsOptions& options) {
  GainsReport report;
  report.robot = model.name();
  report.data = options.data;
  report.loaded = options.loaded;
  report.payload_mass = options.payload_mass;
  DriveGainOptions gains;
  gains.friction = options.friction_model();
  gains.payload_mass = options.payload_mass;
  PreparedLog unloaded = PrepareJointLog(options.data, model, options.preparation(false));
  PreparedLog loaded = PrepareJointLog(options.loaded, model, options.preparation(true));
  for (PreparedLog* log : {&unloaded, &loaded}) {
    for (std::string& note : log->notes) report.notes.push_back(std::move(note));
    for (std::string& warning : log->warnings) report.warnings.push_back(std::move(warning));
  }
  report.n_unloaded = unloaded.log.n_samples();
  report.n_loaded = loaded.log.n_samples();
  report.estimate = EstimateDriveGains(model, ToCurrentLog(std::move(unloaded)), ToCurrentLog(std::move(loaded)), gains);
  return report;
}

std::string FormatGainsTable(const RobotModel& model, const GainsOptions& options, const GainsReport& report) {
  const DriveGainEstimate& e = report.estimate;
  std::string out;
  for (const std::string& note : report.notes) out += note + "\n";
  char line[512];
  out += Headline(report) + "\n\n";
  std::snprintf(line, sizeof(line), "%6s  %14s  %11s  %8s\n", "joint", "K [N m/A]", "sigma", "%sigma");
  out += line;
  for (int j = 0; j < model.n_dof(); ++j) {
    if (!std::isfinite(e.gains[j])) {
      std::snprintf(line, sizeof(line), "%6d  %14s  %11s  %8s\n", j + 1, "not ident.", "-", "-");
    } else {
      std::snprintf(line, sizeof(line), "%6d  %14.6g  %11.3g  %8.3g\n", j + 1, e.gains[j], e.sigma[j],
                    100.0 * e.sigma[j] / std::abs(e.gains[j]));
    }
    out += line;
  }
  out += SigmaMethodText(e.covariance_method, "gains.json") + "\n";
  out += ResidualLine(e) + "\n";
  std::snprintf(line, sizeof(line), "Payload torque / loaded residual: %.3g (at least %g); unloaded K·i / robot file's "
                "torques: %.3g (%g to %g)\n", e.payload_signal_to_noise, DriveGainOptions::kMinPayloadSignalToNoise,
                e.torque_scale, 1.0 / DriveGainOptions::kMaxTorqueScale, DriveGainOptions::kMaxTorqueScale);
  out += line;
  if (e.status != DriveGainStatus::kEstimated) out += e.message + "\n";
  return out;
}

std::string FormatGainsJson(const RobotModel& model, const GainsOptions& options, const GainsReport& report) {
  using nlohmann::json;
  const DriveGainEstimate& e = report.estimate;
  json gains = json::array(), sigma = json::array(), sigma_white = json::array(), payload = json::object();
  for (int j = 0; j < model.n_dof(); ++j) {
    gains.push_back(NumberOrNull(e.gains[j]));
    sigma.push_back(NumberOrNull(e.sigma[j]));
    sigma_white.push_back(NumberOrNull(e.sigma_white[j]));
  }
  for (size_t c = 0; c < PayloadParameterNames().size(); ++c) {
    payload[PayloadParameterNames()[c]] = NumberOrNull(e.payload[static_cast<Eigen::Index>(c)]);
  }
  const json result = {
      {"drive_gains", gains},
      {"sigma", sigma},
      {"sigma_white", sigma_white},
      {"sigma_method", SigmaMethodJson(e.covariance_method, "gains.json")},
      {"command", options.command_line},
      {"robot", model.name()},
      {"unloaded", {{"data", options.data}, {"n_samples", report.n_unloaded}, {"joint_rms", ToStdVector(e.unloaded_rms)},
                    {"relative_error", e.unloaded_relative_error}}},
      {"loaded", {{"data", options.loaded}, {"n_samples", report.n_loaded}, {"joint_rms", ToStdVector(e.loaded_rms)},
                  {"relative_error", e.loaded_relative_error}}},
      {"payload_mass", options.payload_mass},
      {"time_window", options.time_window.empty() ? json(nullptr) : json(options.time_window)},
      {"loaded_time_window", options.loaded_time_window.empty() ? json(nullptr) : json(options.loaded_time_window)},
      {"payload_first_moment_and_inertia", payload},
      {"rank", e.rank},
      {"payload_signal_to_noise", NumberOrNull(e.payload_signal_to_noise)},
      {"torque_scale", NumberOrNull(e.torque_scale)},
      {"n_unknowns", e.unknown_names.size()},
      {"friction", options.friction},
      {"log_preparation", report.notes},
  };
  return result.dump(2) + "\n";
}

}  // namespace idbench
