// The Compare tab (`idbench compare`): the designed motion and the chosen
// built-in ones side by side, their conditioning, Bullet's realised one, the
// Monte Carlo error and whether they keep within the limits.
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

void GuiApp::Impl::DrawCompareTab() {
  CompareOptions& c = session.compare;
  const bool running = session.running(JobKind::kCompare);
  ImGui::BeginDisabled(running);
  ImGui::TextUnformatted(session.design_report() ? "Motions: the designed one, and" : "Motions (no design yet):");
  for (const std::string& name : BuiltinMotionNames()) {
    ImGui::SameLine();
    bool on = std::find(session.compare_builtins.begin(), session.compare_builtins.end(), name) !=
              session.compare_builtins.end();
    if (widgets.Checkbox("compare." + name, name.c_str(), &on)) {
      auto& list = session.compare_builtins;
      list.erase(std::remove(list.begin(), list.end(), name), list.end());
      if (on) list.push_back(name);
    }
  }
  ImGui::PushItemWidth(110);
  widgets.InputInt("compare.samples", "samples", &c.samples, 4, 100000);
  ImGui::SameLine(260);
  widgets.InputInt("compare.trials", "trials", &c.trials, 2, 100000);
  if (c.tau_noise.empty()) c.tau_noise.push_back(0.05);
  widgets.InputDouble("compare.tau_noise", "τ noise σ [N m]", &c.tau_noise[0]);
  ImGui::SameLine(260);
  widgets.InputUnsigned("compare.seed", "seed", &c.seed);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();
  if (JobButton("compare.run", "Compare", !running, running, "comparing (Bullet + Monte Carlo)..."))
    session.StartCompare();

  const auto& report = session.compare_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "No comparison yet.");
    return;
  }
  std::vector<float> bars;
  for (const MotionComparison& m : report->motions)
    bars.push_back(std::isfinite(m.designed.cond) ? static_cast<float>(std::log10(m.designed.cond)) : 0.0f);
  ImGui::PlotHistogram("##compare_bars", bars.data(), static_cast<int>(bars.size()), 0,
                       "log10 cond(W) per motion (0: rank deficient)", 0.0f, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("compare.bars");
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("compare", 8, flags)) {
    for (const char* h : {"motion", "cond", "norm. cond", "log det", "σ_min", "Bullet cond", "mean err", "limits"})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const MotionComparison& m : report->motions) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      const std::string name = m.name == session.OutPath("trajectory.json") ? "designed"
                               : m.name.size() > 24                       ? "..." + m.name.substr(m.name.size() - 21)
                                                                          : m.name;
      TextCell(name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m.name.c_str());
      const double cells[] = {m.designed.cond, m.designed.cond_normalised, m.designed.log_det, m.designed.sigma_min,
                              m.realised.cond, m.mean_relative_error};
      for (int k = 0; k < 6; ++k) {
        ImGui::TableSetColumnIndex(1 + k);
        if (k == 0 && !m.unexcited.empty()) {  // cond(W) = inf: name what the motion leaves undetermined
          TextCell("rank deficient", &kErrorColor);
          if (ImGui::IsItemHovered()) {
            std::string names;
            for (const std::string& n : m.unexcited) names += (names.empty() ? "" : ", ") + n;
            ImGui::SetTooltip("This motion does not determine: %s", names.c_str());
          }
          continue;
        }
        TextCell(Number(cells[k], "%.3g"));
      }
      ImGui::TableSetColumnIndex(7);
      TextCell(m.limits.feasible() ? "ok" : "violated", m.limits.feasible() ? nullptr : &kErrorColor);
      if (!m.limits.feasible() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m.limits.Explain().c_str());
    }
    ImGui::EndTable();
  }
}

}  // namespace idbench::gui
