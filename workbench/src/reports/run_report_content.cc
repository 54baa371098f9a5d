#include "idbench/workbench/reports/report_command.h"

#include "number_format.h"
#include "idbench/workbench/reports/plots.h"

namespace idbench {
namespace {

// The built-in motion a run is compared with: the other one, or the paper's
// for a trajectory file.
std::string OtherMotion(const std::string& motion) { return motion == "paper" ? "general" : "paper"; }

}  // namespace

ReportContent MakeRunReportContent(const RobotModel& model, const RunOptions& options, const RunReport& report,
                                   std::string pose_figure_png) {
  const PerBodyIdentificationResult& r = report.identification;
  ReportContent content;
  content.title = "idbench run: " + model.name() + ", " + options.motion + " motion, per-body quaternion method";
  content.command = options.command_line.empty() ? "idbench run" : options.command_line;
  content.experiment = {
      {"robot", model.name()},
      {"motion", options.motion == "paper" ? "paper: hinges 1 and 2 accelerate at " +
                                                 Format("%g", options.accel_deg_s2) + " deg/s², others locked"
                                           : options.motion == "general"
                                               ? "general: all joints move (two-harmonic Fourier series)"
                                               : "trajectory file " + options.motion},
      {"duration, step", Format("%g", options.duration) + " s, " + Format("%g", options.dt) + " s (Bullet, joint feedback)"},
      {"samples", std::to_string(r.n_samples) + " (" +
                      (options.all_samples ? std::string("every step") : [&] {
                        std::string t;
                        for (double s : options.sample_times) t += (t.empty() ? "" : ", ") + Format("%g", s);
                        return t + " s";
                      }()) + ")"},
      {"largest relative error", Format("%.3e", r.max_rel_error) + " (" + r.max_rel_error_at + "); the paper's: 3.1e-04"}};
  content.pose_figure_png = std::move(pose_figure_png);
  content.pose_caption = "The poses of " + model.name() + " along the " + options.motion + " motion (cf. the paper's Figure 2).";

  // Tables: parameters per body, then the blocks' conditioning.
  ReportTable parameters{"Identified versus true parameters (masses kg, inertias kg m²)",
                         {"body", "parameter", "true", "identified", "abs error", "rel error", "status"},
                         {}};
  ReportTable blocks{"Identifiability per body", {"body", "Newton rank", "Newton cond", "Euler rank", "Euler cond",
                                                   "Euler residual [N m]"}, {}};
  for (const BodyResult& body : r.bodies) {
    for (const ParameterResult& p : body.parameters) {
      parameters.rows.push_back({body.name, p.name, Format("%.6f", p.true_value),
                                 p.identifiable ? Format("%.12g", p.identified) : "-", Format("%.3e", p.abs_error),
                                 Format("%.2e", p.rel_error), p.identifiable ? "ok" : "NOT IDENTIFIABLE: " + p.reason});
    }
    blocks.rows.push_back({body.name, std::to_string(body.newton.rank) + "/" + std::to_string(body.newton.n_unknowns),
                           Format("%.3g", body.newton.cond),
                           std::to_string(body.euler.rank) + "/" + std::to_string(body.euler.n_unknowns),
                           Format("%.3g", body.euler.cond), Format("%.3g", body.euler.residual_norm)});
  }
  content.tables = {parameters, blocks};

  // Plots: signals, parameters, spectra, and this motion against the other one.
  const std::vector<Spectrum> spectra = RunEulerSpectra(model, report.log, report.sample_steps);
  RunOptions other = options;
  other.motion = OtherMotion(options.motion);
  const RunReport other_report = RunExperiment(model, other);
  const std::vector<MotionSummary> motions = {
      SummarizeMotion(options.motion, spectra, r.max_rel_error),
      SummarizeMotion(other.motion, RunEulerSpectra(model, other_report.log, other_report.sample_steps),
                      other_report.identification.max_rel_error)};
  content.plots = {
      {"joints", "Joint positions, velocities, accelerations and torques over time (simulated in Bullet).",
       JointSignalsPlot(SignalsOf(report.log), JointNames(model))},
      {"parameters", "True (bars) and identified (dots, error bars = |error|) parameters; unidentifiable ones have no dot.",
       ParameterPlot("Identified versus true parameters", "true", RunParameterEstimates(r))},
      {"spectrum", "Singular values of each body's column-normalised Euler block over the samples; a missing value is "
                   "zero (a direction the motion does not excite).",
       SpectrumPlot("Singular-value spectrum of the inertia blocks", spectra)},
      {"motions", "The " + options.motion + " motion against the " + other.motion +
                      " motion with the same samples: conditioning, information (log det) and accuracy.",
       MotionComparisonPlot(motions)}};
  return content;
}

}  // namespace idbench
