#include "idbench/workbench/reports/report_command.h"

#include "joint_log_playback.h"
#include "number_format.h"
#include "idbench/workbench/reports/message_list.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/reports/plots.h"

namespace idbench {
namespace {

// "N samples", and when the fit used fewer (a filtered log's ends dropped,
// a decimated one) how many it was identified from and why.
std::string SamplesText(const IdentifyReport& report) {
  std::string text = std::to_string(report.n_samples_read) + " samples";
  const int decimation = report.parallel_filter ? report.parallel_filter->filter.decimation
                         : report.prepared      ? report.prepared->decimation
                                                : 1;
  const std::string kept = decimation > 1 ? "one in " + std::to_string(decimation) + " kept" : "";
  if (report.parallel_filter) {
    return text + ", qd and qdd estimated by zero-phase filtering; " + std::to_string(report.n_samples) +
           " identified from, the filter's ends dropped" + (kept.empty() ? "" : " and " + kept);
  }
  if (report.n_samples == report.n_samples_read) return text;
  return text + "; " + std::to_string(report.n_samples) + " identified from" + (kept.empty() ? "" : ", " + kept);
}

}  // namespace

using internal::JointLogPlayback;

ReportContent MakeIdentifyReportContent(const RobotModel& model, const IdentifyOptions& options,
                                        const IdentifyReport& report, LogOrigin origin) {
  const JointTorqueIdentification& id = report.identification;
  const bool simulated = origin == LogOrigin::kSimulated;
  // The robot file's values: the truth of a log simulated from it, a
  // reference (CAD values, a datasheet) for a recorded one.
  const std::string reference = simulated ? "truth (robot file)" : "robot file";
  const std::vector<std::string> joint_names = JointNames(model);
  ReportContent content;
  content.title = "idbench identify: " + model.name() + " from " + options.data + ", " + std::string(ToString(options.estimator));
  content.command = options.command_line.empty() ? "idbench identify" : options.command_line;
  std::string friction;
  for (const std::string& f : options.friction) friction += (friction.empty() ? "" : ",") + f;
  content.experiment = {{"robot", model.name()},
                        {simulated ? "simulated log" : "recorded log",
                         options.data + " (" + SamplesText(report) + ")"},
                        {"estimator", std::string(ToString(options.estimator))},
                        {"friction", friction},
                        {"cond(W)", id.linear.rank < id.base.n_base()
                                        ? "inf: rank " + std::to_string(id.linear.rank) + " of " +
                                              std::to_string(id.base.n_base()) + " (parameters not identifiable below)"
                                        : Format("%.4g", id.linear.cond)},
                        {"σ", SigmaMethodText(id.linear).substr(7)},  // without "sigma: "
                        {"relative torque error (fit)", Format("%.4g", id.fit.relative_error)},
                        {"relative torque error (robot file)", Format("%.4g", id.model_fit.relative_error)}};
  if (report.validation) {
    content.experiment.push_back({"relative torque error (validation on " + options.validate + ")",
                                  Format("%.4g", report.validation->relative_error)});
  }
  for (const std::string& warning : CollapseRepeatedMessages(report.warnings)) {
    content.experiment.push_back({"warning", warning});
  }
  // The poses along the log.
  if (report.log.n_samples() >= 2) {
    const JointLogPlayback playback(report.log);
    PoseFigureOptions figure;
    figure.times = DefaultFigureTimes(playback.duration());
    content.pose_figure_png = RenderPoseFigurePng(model, playback, figure);
    content.pose_caption = "The poses of " + model.name() + " along the log (times from its first sample).";
  }
  ReportTable base{simulated ? "Base parameters identified from the simulated log against the truth (the robot file "
                               "that generated it)"
                             : "Base parameters identified from the recorded log, with the robot file's values for "
                               "reference",
                   {"#", "base parameter", "identified", "σ", "%σ", "status", reference,
                    simulated ? "error" : "identified − robot file"},
                   {}};
  std::vector<ParameterEstimate> estimates;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const std::string& name = id.base.names[static_cast<size_t>(k)];
    const std::string status = ToString(ClassifyParameter(id.beta[k], id.linear.sigma[k]));
    if (!id.linear.identifiable[static_cast<size_t>(k)]) {  // no number: the log does not determine it
      base.rows.push_back({std::to_string(k + 1), name, "-", "-", "-", status, Format("%.6g", id.beta_model[k]), "-"});
      continue;
    }
    base.rows.push_back({std::to_string(k + 1), name, Format("%.6g", id.beta[k]), Format("%.3g", id.linear.sigma[k]),
                         Format("%.3g", RelativeSigmaPercent(id.beta[k], id.linear.sigma[k])), status,
                         Format("%.6g", id.beta_model[k]),
                         Format("%.3g", id.beta[k] - id.beta_model[k])});
    estimates.push_back({std::to_string(k + 1), id.beta_model[k], id.beta[k], 3.0 * id.linear.sigma[k]});
  }
  ReportTable fit{"Torque RMS per joint [N m]", {"joint", "fit", "robot file"}, {}};
  for (Eigen::Index j = 0; j < id.fit.joint_rms.size(); ++j) {
    fit.rows.push_back({JointLabel(joint_names, j), Format("%.4g", id.fit.joint_rms[j]), Format("%.4g", id.model_fit.joint_rms[j])});
  }
  if (report.validation) {
    fit.header.push_back("validation");
    for (Eigen::Index j = 0; j < id.fit.joint_rms.size(); ++j) {
      fit.rows[static_cast<size_t>(j)].push_back(Format("%.4g", report.validation->joint_rms[j]));
    }
  }
  ReportTable unexcited{"Standard parameters with no effect on the torques (not identifiable)", {"parameter"}, {}};
  for (int c : id.base.unexcited) unexcited.rows.push_back({id.standard_names[static_cast<size_t>(c)]});
  content.tables = {base, fit};
  if (!unexcited.rows.empty()) content.tables.push_back(unexcited);
  const Eigen::MatrixXd W = StackBaseRegressor(model, options.friction_model(), id.base, report.log);
  content.plots = {
      {"joints", std::string("The ") + (simulated ? "simulated" : "recorded") + " joint log as identified.",
       JointSignalsPlot(SignalsOf(report.log), joint_names)},
      {"parameters", "Base parameters: " + reference + " (bars) and identified (dots) ± 3σ; numbered as in the table.",
       ParameterPlot(simulated ? "Identified versus true base parameters" : "Identified and robot-file base parameters",
                     reference, estimates)},
      {"spectrum", "Singular values of the column-normalised base regressor W stacked over the log.",
       SpectrumPlot("Singular-value spectrum of the base regressor", {{"W", NormalizedSingularValues(W)}})}};
  // Measured against predicted torque, τ̂ = W β of the chosen estimator, on
  // the equations the RMS numbers score (parallel-filtered as they are).
  const std::string how = " (τ̂ = W β, " + std::string(ToString(options.estimator)) + "): ";
  const auto filtered = [](const std::optional<ParallelFilter>& filter) {
    return filter ? "both parallel-filtered, the filter's ends dropped, as in the torque RMS." : "as in the torque RMS.";
  };
  // A simulated log's torques come from its simulated sensors.
  const std::string measured = simulated ? "simulated" : "measured";
  const std::string measured_caption = simulated ? "Simulated" : "Measured";
  content.plots.push_back({"torques", measured_caption + " and predicted joint torque on the identification log" + how +
                                          filtered(report.parallel_filter),
                           TorqueComparisonPlot(PredictIdentifiedTorques(model, options, report, false),
                                                {"identification log", measured, joint_names})});
  if (report.held_out_log) {
    content.plots.push_back(
        {"validation_torques", measured_caption + " and predicted joint torque on the held-out log " + options.validate + how +
                                   filtered(report.held_out_filter),
         TorqueComparisonPlot(PredictIdentifiedTorques(model, options, report, true),
                              {"held-out log", measured, joint_names})});
  }
  return content;
}

}  // namespace idbench
