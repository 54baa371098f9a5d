#include "run_command.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>

#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

constexpr double kPaperMaxRelError = 3.1e-4;  // the paper's Table 3: 0.031 %

std::string Num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

nlohmann::json NumberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

bool RunOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    *why = message;
    return false;
  };
  if (robot != "paper6r") return fail("--robot: unknown robot '" + robot + "' (built-in: paper6r)");
  if (motion != "paper" && motion != "general")
    return fail("--motion: expected 'paper' or 'general', got '" + motion + "'");
  if (!std::isfinite(accel_deg_s2) || accel_deg_s2 <= 0.0)
    return fail("--accel: must be > 0 deg/s^2, got " + Num(accel_deg_s2));
  if (!std::isfinite(dt) || dt <= 0.0) return fail("--dt: must be > 0 s, got " + Num(dt));
  if (!std::isfinite(duration) || duration <= 0.0) return fail("--duration: must be > 0 s, got " + Num(duration));
  if (duration < 2.0 * dt)
    return fail("--duration: " + Num(duration) + " s is shorter than two steps of --dt " + Num(dt) + " s");
  if (duration / dt > 1e8) return fail("--duration/--dt: " + Num(duration / dt) + " steps is more than 1e8");
  if (all_samples) return true;
  // Samples need the next step for the acceleration: t in [0, duration − dt].
  const double last = duration - dt;
  std::set<long long> steps;
  for (double t : sample_times) {
    if (!std::isfinite(t) || t < 0.0 || t > last + 1e-9 * duration) {
      return fail("--samples: time " + Num(t) + " s is outside the run [0, " + Num(last) + "] s");
    }
    if (!steps.insert(std::llround(t / dt)).second) {
      return fail("--samples: time " + Num(t) + " s falls on the same step as another sample");
    }
  }
  if (static_cast<int>(sample_times.size()) < kMinSamples) {
    return fail("--samples: " + std::to_string(sample_times.size()) + " sample time(s) given, need at least " +
                std::to_string(kMinSamples) + " (the unknowns per body: m, J11, J22, J33)");
  }
  return true;
}

RunReport RunExperiment(const RobotModel& model, const RunOptions& options) {
  const std::unique_ptr<Trajectory> motion =
      options.motion == "general"
          ? MakeGeneralMotion(model.n_dof(), options.duration)
          : MakePaperMotion(model.n_dof(), options.accel_deg_s2 * std::numbers::pi / 180.0, options.duration);
  SimulationOptions sim;
  sim.dt = options.dt;
  sim.duration = options.duration;
  RunReport report;
  report.log = Simulate(model, *motion, sim);
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
  std::snprintf(line, sizeof(line),
                "idbench run: %s, %s motion, %.0f steps of %g s, %d samples, per-body quaternion method\n\n",
                options.robot.c_str(), options.motion.c_str(), options.duration / options.dt, options.dt,
                r.n_samples);
  out += line;
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
  std::snprintf(line, sizeof(line),
                "largest relative error over identifiable parameters: %.3e (%s); the paper's: %.1e\n",
                r.max_rel_error, r.max_rel_error_at.c_str(), kPaperMaxRelError);
  out += line;
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
