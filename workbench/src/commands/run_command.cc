#include "idbench/workbench/commands/run_command.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/excitation/builtin_motions.h"
#include "number_format.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "formats/json_number.h"

namespace idbench {
namespace {

constexpr double kPaperMaxRelError = 3.1e-4;  // the paper's Table 3: 0.031 %


// "idbench run: paper6r, paper motion, ..." without its newline.
std::string Headline(const RunReport& report) {
  char line[256];
  std::snprintf(line, sizeof(line), "idbench run: %s, %s motion, %.0f steps of %g s, %d samples, per-body quaternion method",
                report.robot.c_str(), report.motion.c_str(), report.duration / report.dt, report.dt,
                report.identification.n_samples);
  return line;
}

// "largest relative error over identifiable parameters: ..." without its newline.
std::string LargestError(const PerBodyIdentificationResult& r) {
  char line[256];
  std::snprintf(line, sizeof(line), "largest relative error over identifiable parameters: %.3e (%s); the paper's: %.1e",
                r.max_rel_error, r.max_rel_error_at.c_str(), kPaperMaxRelError);
  return line;
}

}  // namespace

std::string RunReport::BriefReport() const {
  int n_parameters = 0, n_identified = 0;
  std::string unidentified;  // "B1.m_e1, ..."
  for (const BodyResult& body : identification.bodies) {
    for (const ParameterResult& p : body.parameters) {
      ++n_parameters;
      if (p.identifiable) ++n_identified;
      else unidentified += (unidentified.empty() ? "" : ", ") + body.name + "." + p.name;
    }
  }
  std::string out = Headline(*this) + "\n" + std::to_string(n_identified) + " of " + std::to_string(n_parameters) +
                    " parameters identified";
  if (!unidentified.empty()) out += "; not identifiable: " + unidentified;
  return out + "\n" + LargestError(identification) + "\n";
}

SimulationOptions RunOptions::simulation() const {
  SimulationOptions sim;
  sim.dt = dt;
  sim.duration = duration;
  return sim;
}

std::unique_ptr<Trajectory> MakeRunMotion(const RobotModel& model, const RunOptions& options) {
  const BuiltinMotionOptions builtin{.duration = options.duration,
                                     .paper_qdd = options.accel_deg_s2 * std::numbers::pi / 180.0};
  std::unique_ptr<Trajectory> motion = LoadTrajectoryArg(options.motion, model, builtin);
  if (motion->duration() < options.duration - 1e-9) {
    throw std::invalid_argument(options.motion + ": lasts " + Shortest(motion->duration()) +
                                " s, shorter than `duration` " + Shortest(options.duration) + " s");
  }
  return motion;
}

bool RunOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (robot != "paper6r") return fail("robot: unknown robot '" + robot + "' (built-in: paper6r)");
  if (motion != "paper" && motion != "general" && !IsTrajectoryFile(motion))
    return fail("motion: expected 'paper', 'general' or a trajectory file (.json, .csv), got '" + motion + "'");
  if (!std::isfinite(accel_deg_s2) || accel_deg_s2 <= 0.0 || accel_deg_s2 > kMaxAccelDegS2)
    return fail("accel_deg_s2: must be in (0, " + Shortest(kMaxAccelDegS2) + "] deg/s^2, got " + Shortest(accel_deg_s2));
  if (!std::isfinite(dt) || dt <= 0.0) return fail("dt: must be > 0 s, got " + Shortest(dt));
  if (!std::isfinite(duration) || duration <= 0.0) return fail("duration: must be > 0 s, got " + Shortest(duration));
  // A whole number of steps, so that the run is exactly as long as asked.
  const double steps = duration / dt;
  if (std::abs(steps - std::round(steps)) > 1e-6 * steps)
    return fail("duration: " + Shortest(duration) + " s is not a whole number of steps (dt: " + Shortest(dt) + " s)");
  std::string sim_why;
  if (!simulation().IsValid(&sim_why)) return fail("dt: " + sim_why);
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  if (all_samples) return true;
  // Samples lie on the step grid and need the next step for the
  // acceleration: t = n·dt with n in [0, steps − 1].
  const long long n_steps = std::llround(steps);
  std::set<long long> used;
  for (double t : sample_times) {
    const double n = t / dt;
    if (!std::isfinite(t) || std::llround(n) < 0 || std::llround(n) > n_steps - 1) {
      return fail("sample_times: time " + Shortest(t) + " s is outside the run [0, " + Shortest((n_steps - 1) * dt) + "] s");
    }
    if (std::abs(n - std::round(n)) > 1e-6) {
      return fail("sample_times: time " + Shortest(t) + " s is not on the step grid (dt: " + Shortest(dt) + " s)");
    }
    if (!used.insert(std::llround(n)).second) return fail("sample_times: time " + Shortest(t) + " s is given twice");
  }
  if (static_cast<int>(sample_times.size()) < kMinSamples) {
    return fail("sample_times: " + std::to_string(sample_times.size()) + " sample time(s) given, need at least " +
                std::to_string(kMinSamples) + " (the unknowns per body: m, J11, J22, J33)");
  }
  return true;
}

RunReport RunExperiment(const RobotModel& model, const RunOptions& options) {
  const std::unique_ptr<Trajectory> motion = MakeRunMotion(model, options);
  RunReport report;
  report.robot = options.robot;
  report.motion = options.motion;
  report.duration = options.duration;
  report.dt = options.dt;
  report.log = Simulate(model, *motion, options.simulation());
  if (options.all_samples) {
    for (int n = 0; n < static_cast<int>(report.log.steps.size()); ++n) report.sample_steps.push_back(n);
  } else {
    for (double t : options.sample_times) report.sample_steps.push_back(report.log.StepAt(t));
  }
  report.identification = IdentifyPerBody(model, report.log, report.sample_steps);
  return report;
}

std::string FormatRunTables(const RunOptions& options, const RunReport& report) {
  std::string out;
  char line[256];
  const PerBodyIdentificationResult& r = report.identification;
  out += Headline(report) + "\n\n";
  for (const BodyResult& body : r.bodies) {
    std::snprintf(line, sizeof(line), "%-4s %-5s %16s %20s %12s %10s  %s\n", body.name.c_str(), "param", "true",
                  "identified", "abs error", "rel error", "status");
    out += line;
    for (const ParameterResult& p : body.parameters) {
      if (p.identifiable) {
        std::snprintf(line, sizeof(line), "     %-5s %16.6f %20.12f %12.3e %10.2e  ok\n", p.name.c_str(),
                      p.true_value, p.identified, p.abs_error, p.rel_error);
      } else {
        std::snprintf(line, sizeof(line), "     %-5s %16.6f %20s %12s %10s  NOT IDENTIFIABLE: %s\n",
                      p.name.c_str(), p.true_value, "-", "-", "-", p.reason.c_str());
      }
      out += line;
    }
    std::snprintf(line, sizeof(line), "     inertia block: rank %d/3, cond %.3g, residual %.3g N m\n\n",
                  body.euler.rank, body.euler.cond, body.euler.residual_norm);
    out += line;
  }
  out += LargestError(r) + "\n";
  return out;
}

std::string FormatRunResultsJson(const RunOptions& options, const RunReport& report) {
  const PerBodyIdentificationResult& r = report.identification;
  nlohmann::json j;
  j["command"] = options.command_line;
  j["robot"] = options.robot;
  j["method"] = "per-body quaternion (paper eqs. 17, 18, 24-27)";
  j["motion"] = options.motion;
  if (options.motion == "paper") j["accel_deg_s2"] = options.accel_deg_s2;
  j["duration"] = options.duration;
  j["dt"] = options.dt;
  j["n_steps"] = report.log.steps.size();
  std::vector<double> times;
  for (int s : report.sample_steps) times.push_back(report.log.steps[static_cast<size_t>(s)].t);
  j["sample_times"] = times;
  j["bodies"] = nlohmann::json::array();
  for (const BodyResult& body : r.bodies) {
    nlohmann::json b;
    b["name"] = body.name;
    b["parameters"] = nlohmann::json::array();
    for (const ParameterResult& p : body.parameters) {
      b["parameters"].push_back({{"name", p.name},
                                 {"true", p.true_value},
                                 {"identified", NumberOrNull(p.identified)},
                                 {"identifiable", p.identifiable},
                                 {"reason", p.reason},
                                 {"abs_error", NumberOrNull(p.abs_error)},
                                 {"rel_error", NumberOrNull(p.rel_error)}});
    }
    for (const auto& [key, block] : {std::pair{"newton", body.newton}, std::pair{"euler", body.euler}}) {
      b[key] = {{"rank", block.rank},
                {"unknowns", block.n_unknowns},
                {"cond", block.cond},
                {"residual_norm", block.residual_norm}};
    }
    j["bodies"].push_back(b);
  }
  j["max_rel_error"] = r.max_rel_error;
  j["max_rel_error_at"] = r.max_rel_error_at;
  j["paper_max_rel_error"] = kPaperMaxRelError;
  return j.dump(2) + "\n";
}

}  // namespace idbench
