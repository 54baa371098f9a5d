// The Experiment tab: simulate a log of the chosen motion and identify the
// joint-torque model's base parameters from it (`idbench simulate`,
// `idbench identify`), or run the per-body experiment (`idbench run`).
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench::gui {
namespace {

std::vector<std::string> MotionNames(bool with_designed) {
  std::vector<std::string> names;
  if (with_designed) names.push_back("designed");
  for (const std::string& n : BuiltinMotionNames()) names.push_back(n);
  return names;
}

}  // namespace

void GuiApp::Impl::DrawExperimentTab() {
  SimulateOptions& s = session.simulate;
  IdentifyOptions& id = session.identify;
  const bool busy = session.running(JobKind::kSimulate) || session.running(JobKind::kIdentify) ||
                    session.running(JobKind::kPerBody);
  ImGui::PushItemWidth(110);
  ImGui::BeginDisabled(busy);
  widgets.Combo("experiment.motion", "motion", &session.motion, MotionNames(true));
  ImGui::SameLine(260);
  ImGui::BeginDisabled(session.motion == "designed");  // a designed motion is one period
  widgets.InputDouble("experiment.duration", "duration [s]", &session.builtin_duration);
  ImGui::EndDisabled();
  widgets.Combo("identify.model", "identification model", &id.model, kIdentificationModelNames);
  ImGui::EndDisabled();
  if (id.model == IdentificationModel::kPerBody) {
    ImGui::PopItemWidth();
    DrawPerBodyExperiment(busy);
    return;
  }
  ImGui::BeginDisabled(busy);
  if (s.sensors.tau_noise.empty()) s.sensors.tau_noise.push_back(0.0);
  widgets.InputDouble("experiment.tau_noise", "τ noise σ [N m]", &s.sensors.tau_noise[0]);
  ImGui::SameLine(260);
  widgets.InputDouble("experiment.tau_noise_bandwidth", "τ noise band [Hz] (0: white)", &s.sensors.tau_noise_bandwidth_hz);
  widgets.InputDouble("experiment.q_noise", "q noise σ [rad]", &s.sensors.q_noise);
  ImGui::SameLine(260);
  widgets.InputUnsigned("experiment.seed", "noise seed", &s.sensors.seed);
  widgets.InputDouble("experiment.rate", "rate [Hz]", &s.sensors.rate_hz);
  ImGui::EndDisabled();
  if (widgets.Button("experiment.simulate", "Simulate", !busy)) session.StartSimulate();
  ImGui::SameLine();
  if (session.log()) ImGui::Text("log: %d samples", session.log()->n_samples());
  else if (session.running(JobKind::kSimulate)) ImGui::Text("simulating...");
  else ImGui::TextColored(kDimColor, "no log yet");

  ImGui::BeginDisabled(busy);
  widgets.Combo("identify.estimator", "estimator", &id.estimator, kTorqueEstimatorNames);
  ImGui::EndDisabled();
  ImGui::PopItemWidth();
  ImGui::SameLine();
  if (JobButton("experiment.identify", "Identify", !busy && session.log().has_value(),
                session.running(JobKind::kIdentify), "identifying..."))
    session.StartIdentify();

  const auto& report = session.identify_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "Nothing identified yet (joint-torque model, base parameters).");
    return;
  }
  const std::vector<IdentifiedRow> rows = session.IdentifiedRows();
  const JointTorqueIdentification& ident = report->identification;
  ImGui::Text("%d base parameters, cond(W) %.4g, torque error %.3g%% (robot file %.3g%%)", ident.base.n_base(),
              ident.linear.cond, 100 * ident.fit.relative_error, 100 * ident.model_fit.relative_error);
  if (ident.linear.rank < ident.base.n_base()) {
    ImGui::TextColored(kErrorColor, "This log determines only %d combinations (rank): the motion does not excite the "
                       "rows marked n/a.", ident.linear.rank);
  }
  // Bars: |relative error| per base parameter [%].
  std::vector<float> bars;
  for (const IdentifiedRow& row : rows) bars.push_back(std::isnan(row.relative_error) ? 0.0f : static_cast<float>(100 * std::abs(row.relative_error)));
  ImGui::PlotHistogram("##bars", bars.data(), static_cast<int>(bars.size()), 0, "|error| per base parameter [%]", 0.0f,
                       FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("experiment.bars");

  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_Resizable;
  const std::vector<std::string> unexcited = session.UnexcitedParameters();
  const float reserve = unexcited.empty() ? 0.0f : 2.5f * ImGui::GetTextLineHeightWithSpacing();
  if (ImGui::BeginTable("identified", 6, flags, ImVec2(0, ImGui::GetContentRegionAvail().y - reserve))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("base parameter", ImGuiTableColumnFlags_WidthStretch);
    for (const char* c : {"true", "identified", "error %", "%σ", "flag"}) ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthFixed, 0.0f);
    ImGui::TableHeadersRow();
    for (const IdentifiedRow& row : rows) {
      ImGui::TableNextRow();
      const bool missing = row.status == ParameterStatus::kNotIdentifiable;
      const ImVec4* color = row.status == ParameterStatus::kPoor || missing             ? &kErrorColor
                            : row.status == ParameterStatus::kIndistinguishableFromZero ? &kDimColor
                                                                                         : nullptr;
      ImGui::TableSetColumnIndex(0);
      TextCell(row.name, color);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.name.c_str());
      ImGui::TableSetColumnIndex(1);
      TextCell(Number(row.model_value, "%.5g"), color);
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(row.identified, "%.5g"), color);
      ImGui::TableSetColumnIndex(3);
      TextCell(Number(100 * row.relative_error, "%.2g"), color);
      ImGui::TableSetColumnIndex(4);
      TextCell(Number(row.sigma_percent, "%.2g"), color);
      ImGui::TableSetColumnIndex(5);
      const bool zero = row.status == ParameterStatus::kIndistinguishableFromZero;
      TextCell(row.status == ParameterStatus::kDetermined ? "ok" : zero ? "~0" : missing ? "n/a" : "poor", color);
      if (missing && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Not identifiable: this log does not excite it (W is rank deficient); no value is given");
      }
      if (zero && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("|identified| <= %g σ: the data cannot tell it from zero (a parameter that is 0, or one "
                          "this motion hardly excites)", kZeroSigmas);
      } else if (row.status == ParameterStatus::kPoor && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%%σ above %g %%: poorly identified by this motion", kDeterminedSigmaPercent);
      }
    }
    ImGui::EndTable();
  }
  if (!unexcited.empty()) {
    std::string text = "Not identifiable (no effect on any torque):";
    for (const std::string& n : unexcited) text += " " + n;
    ImGui::TextWrapped("%s", text.c_str());
  }
}

// The per-body experiment (`idbench run`): Bullet's hinge wrenches along the
// motion, every body's mass and principal inertias, or why not.
void GuiApp::Impl::DrawPerBodyExperiment(bool busy) {
  RunOptions& run = session.per_body;
  ImGui::BeginDisabled(busy);
  widgets.Checkbox("per_body.all_samples", "every step (else the paper's 5 instants)", &run.all_samples);
  ImGui::EndDisabled();
  if (JobButton("experiment.per_body", "Run per-body experiment", !busy, session.running(JobKind::kPerBody),
                "simulating and identifying..."))
    session.StartPerBody();
  const auto& result = session.per_body_result();
  if (!result) {
    ImGui::TextColored(kDimColor, "No per-body identification yet (hinge wrenches, no sensor noise).");
    return;
  }
  ImGui::Text("%d samples; largest relative error %.3g (%s)", result->n_samples, result->max_rel_error,
              result->max_rel_error_at.c_str());
  std::vector<float> bars;
  for (const BodyResult& body : result->bodies)
    for (const ParameterResult& p : body.parameters)
      bars.push_back(p.identifiable ? static_cast<float>(std::log10(std::max(p.rel_error, 1e-16)) + 16) : 0.0f);
  ImGui::PlotHistogram("##per_body_bars", bars.data(), static_cast<int>(bars.size()), 0,
                       "16 + log10 relative error per parameter (0: not identifiable)", 0.0f, FLT_MAX,
                       ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("experiment.per_body_bars");
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY;
  if (ImGui::BeginTable("per_body", 5, flags, ImVec2(0, ImGui::GetContentRegionAvail().y))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* c : {"parameter", "true", "identified", "rel. error"})
      ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthFixed, 85.0f);
    ImGui::TableSetupColumn("status", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (const BodyResult& body : result->bodies) {
      for (const ParameterResult& p : body.parameters) {
        ImGui::TableNextRow();
        const ImVec4* color = p.identifiable ? nullptr : &kErrorColor;
        ImGui::TableSetColumnIndex(0);
        TextCell(body.name + "." + p.name, color);
        ImGui::TableSetColumnIndex(1);
        TextCell(Number(p.true_value, "%.6g"), color);
        ImGui::TableSetColumnIndex(2);
        TextCell(Number(p.identified, "%.6g"), color);
        ImGui::TableSetColumnIndex(3);
        TextCell(Number(p.rel_error, "%.2g"), color);
        ImGui::TableSetColumnIndex(4);
        TextCell(p.identifiable ? "ok" : "NOT IDENTIFIABLE", color);
        if (!p.identifiable && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.reason.c_str());
      }
    }
    ImGui::EndTable();
  }
}

}  // namespace idbench::gui
