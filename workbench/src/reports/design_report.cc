#include "idbench/workbench/reports/design_report.h"

#include <cmath>

#include "idbench/engine/inverse_dynamics.h"
#include "number_format.h"
#include "idbench/workbench/reports/plots.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/formats/scene_file.h"

namespace idbench {
namespace {

std::vector<std::string> IdentifiabilityRow(const std::string& what, const Identifiability& id) {
  return {what, Format("%.5g", id.cond), Format("%.5g", id.cond_normalised), Format("%.5g", id.log_det),
          Format("%.5g", id.sigma_min), Format("%.5g", id.sigma_max)};
}

const std::vector<std::string> kIdentifiabilityHeader{"", "cond(W)", "normalised cond", "log det(WᵀW/m)",
                                                      "σ_min", "σ_max"};

// q, qd, qdd of a motion and the motor torques it needs (inverse dynamics
// plus the joint dynamics), at up to 1000 instants.
JointSignals MotionSignals(const RobotModel& model, const Trajectory& motion) {
  constexpr int kSamples = 1000;
  const int n = model.n_dof();
  JointSignals s;
  s.q.resize(kSamples, n);
  s.qd.resize(kSamples, n);
  s.qdd.resize(kSamples, n);
  s.tau.resize(kSamples, n);
  RobotData data(model);
  JointState x(n);
  for (int k = 0; k < kSamples; ++k) {
    const double t = motion.duration() * k / (kSamples - 1);
    motion.Evaluate(t, &x);
    Eigen::VectorXd tau = InverseDynamics(model, x.q, x.qd, x.qdd, &data);
    AddJointDynamicsTorque(model, x.qd, x.qdd, &tau);
    s.t.push_back(t);
    s.q.row(k) = x.q.transpose();
    s.qd.row(k) = x.qd.transpose();
    s.qdd.row(k) = x.qdd.transpose();
    s.tau.row(k) = tau.transpose();
  }
  return s;
}

}  // namespace

ReportContent MakeDesignReportContent(const RobotModel& model, const DesignCommandOptions& options,
                                      const DesignCommandReport& report) {
  const DesignResult& r = report.result;
  const DesignOptions design = options.Resolved();
  ReportContent content;
  content.title = "idbench design: " + model.name() + ", " + std::string(kIdentificationModelNames.Name(options.model)) + " model";
  content.command = options.command_line;
  content.experiment = {
      {"criterion", DesignCriterionName(design.criterion) + ": " + Format("%.6g", r.initial_value) + " → " +
                        Format("%.6g", r.value)},
      {"trajectory", "Fourier series, " + std::to_string(design.harmonics) + " harmonics of " +
                         Format("%g", design.f0) + " Hz over " + Format("%g", design.period_duration()) + " s" +
                         (design.rest_to_rest ? ", rest to rest" : "")},
      {"samples", std::to_string(design.samples)},
      {"search", DesignAlgorithmName(design.algorithm) + ", " + std::to_string(design.starts) + " starts from seed " +
                     std::to_string(design.seed) + ", " + std::to_string(r.evaluations) + " evaluations in " +
                     Format("%.3g", r.wall_seconds) + " s"},
      {"limits", (options.limits.empty() ? "robot file" : options.limits) + ", tightened by " +
                     Format("%g", 100 * design.margin) + " % in the search"},
      {"clearance", design.clearance >= 0.0 ? Format("%g", design.clearance) + " m" : "not checked"},
      {"check at " + Format("%g", r.check.rate_hz) + " Hz", r.check.feasible() ? "feasible" : "INFEASIBLE"},
  };
  PoseFigureOptions figure;
  figure.times = DefaultFigureTimes(r.trajectory.duration());
  // The robot where it stands, in its cell (the scene file read again: RunDesign keeps its copy).
  figure.base_pose = design.base_pose;
  figure.scene = options.scene.empty() ? design.scene : ReadSceneFile(options.scene);
  content.pose_figure_png = RenderPoseFigurePng(model, r.trajectory, figure);
  content.pose_caption = "The poses of " + model.name() + " along the designed motion.";
  content.tables.push_back({"Identifiability of W on the design grid (cond of W itself, never of WᵀW)",
                            kIdentifiabilityHeader,
                            {IdentifiabilityRow("start", r.initial), IdentifiabilityRow("designed", r.final)}});
  ReportTable margins{"Worst instant of every limit at " + Format("%g", r.check.rate_hz) + " Hz",
                      {"joint / pair", "quantity", "value", "limit", "margin", "t [s]"},
                      {}};
  for (const ConstraintMargin& m : r.check.margins) {
    margins.rows.push_back({m.quantity == "clearance" ? m.pair : std::to_string(m.joint + 1), m.quantity,
                            Format("%.5g", m.value), Format("%.5g", m.limit), Format("%.3g", m.margin),
                            Format("%.4g", m.time)});
  }
  content.tables.push_back(std::move(margins));
  ReportTable starts{"Starts", {"start", "seed", "initial", "best", "evaluations", "status"}, {}};
  for (size_t s = 0; s < r.starts.size(); ++s) {
    starts.rows.push_back({std::to_string(s + 1), std::to_string(design.seed + s),
                           Format("%.6g", r.starts[s].initial_value), Format("%.6g", r.starts[s].best_value),
                           std::to_string(r.starts[s].evaluations), r.starts[s].status});
  }
  content.tables.push_back(std::move(starts));
  const DesignRegressor regressor = options.MakeRegressor(model);
  const std::vector<double> times = DesignSampleTimes(design);
  content.plots = {
      {"joints", "The designed motion and the motor torques it needs (inverse dynamics with friction).",
       JointSignalsPlot(MotionSignals(model, r.trajectory), JointNames(model))},
      {"spectrum", "Singular values of the column-normalised W: the start and the design.",
       SpectrumPlot("Singular-value spectrum of W",
                    {{"start", NormalizedSingularValues(regressor.Stack(r.initial_trajectory, times))},
                     {"designed", NormalizedSingularValues(regressor.Stack(r.trajectory, times))}})}};
  return content;
}

ReportContent MakeCompareReportContent(const CompareOptions& options, const CompareReport& report) {
  ReportContent content;
  content.title = "idbench compare: " + options.robot + ", " + std::string(kIdentificationModelNames.Name(options.model)) + " model";
  content.command = options.command_line;
  content.experiment = {{"samples per motion", std::to_string(options.samples)},
                        {"Monte-Carlo trials", std::to_string(options.trials) + " (seed " +
                                                   std::to_string(options.seed) + ")"},
                        {"parameters", std::to_string(report.parameter_names.size())}};
  ReportTable table{"Motions (designed: the analytic motion; realised: the states Bullet executed)",
                    {"motion", "cond(W)", "normalised cond", "log det(WᵀW/m)", "σ_min", "realised cond",
                     "Monte-Carlo error", "limits"},
                    {}};
  std::vector<MotionSummary> summaries;
  for (const MotionComparison& m : report.motions) {
    table.rows.push_back({m.name, Format("%.5g", m.designed.cond), Format("%.5g", m.designed.cond_normalised),
                          Format("%.5g", m.designed.log_det), Format("%.5g", m.designed.sigma_min),
                          Format("%.5g", m.realised.cond), Format("%.4g", m.mean_relative_error),
                          m.limits.feasible() ? "within" : "violated"});
    summaries.push_back({m.name, m.designed.cond, m.designed.log_det / std::log(10.0), m.mean_relative_error});
  }
  content.tables.push_back(std::move(table));
  if (options.model == IdentificationModel::kJointTorque && !report.motions.empty()) {
    ReportTable sigma{"Predicted %σ per base parameter (WLS covariance)", {"#", "parameter"}, {}};
    for (size_t m = 0; m < report.motions.size(); ++m) sigma.header.push_back(report.motions[m].name);
    for (size_t k = 0; k < report.parameter_names.size(); ++k) {
      std::vector<std::string> row{std::to_string(k + 1), report.parameter_names[k]};
      for (const MotionComparison& m : report.motions) {
        row.push_back(Format("%.4g", m.predicted_percent_sigma[static_cast<Eigen::Index>(k)]));
      }
      sigma.rows.push_back(std::move(row));
    }
    content.tables.push_back(std::move(sigma));
  }
  content.plots = {{"motions", "cond(W), log10 det(WᵀW/m) and the Monte-Carlo error per motion.",
                    MotionComparisonPlot(summaries, {"cond(W)", "log10 det(WᵀW/m)", "Monte-Carlo error"})}};
  return content;
}

}  // namespace idbench
