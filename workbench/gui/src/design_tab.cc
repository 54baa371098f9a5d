// The Design tab (`idbench design`): the excitation design's options, a live
// curve of the best criterion while it runs, then the initial and designed
// conditioning and every constraint's margin.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <exception>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/workbench/formats/limits_file.h"

namespace idbench::gui {

// The cell and the mounting: the scene file (DesignCommandOptions::scene, read
// again by the viewport when edited; its errors go to the messages) and the
// base pose (DesignOptions::base_pose), which compare uses too; the limits
// file and the transmission its motor limits act through (as `idbench design`
// --limits and --transmission).
void GuiApp::Impl::DrawDesignCell() {
  DesignCommandOptions& d = session.design;
  if (!design_fields_initialised) {
    for (double v : d.design.base_pose.xyz_rpy) base_pose_text += (base_pose_text.empty() ? "" : ",") + Number(v, "%.17g");
    design_fields_initialised = true;
  }
  ImGui::PushItemWidth(-150);
  ImGui::InputText("scene (JSON)##design.scene", &d.scene);
  if (ImGui::IsItemDeactivatedAfterEdit()) scene_dirty = true;
  widgets.Record("design.scene", [this](const std::string& text, std::string*) {
    session.design.scene = text;
    scene_dirty = true;
    return true;
  });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Obstacles in the world frame (boxes, cylinders, spheres, meshes); empty: the floor only");
  ImGui::InputText("limits (JSON)##design.limits", &d.limits);
  if (ImGui::IsItemDeactivatedAfterEdit()) ReadDesignLimitsFile();
  widgets.Record("design.limits", [this](const std::string& text, std::string*) {
    session.design.limits = text;
    ReadDesignLimitsFile();
    return true;
  });
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Its joint limits go into the table; its \"actuators\" (motor qd_max, tau_max) bound the motors "
                      "through the transmission; empty: the table alone");
  }
  ImGui::InputText("transmission##design.transmission", &d.transmission);
  widgets.Record("design.transmission", [this](const std::string& text, std::string*) {
    session.design.transmission = text;
    return true;
  });
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("What the limits file's actuators act through: urdf (the robot URDF's) or a JSON/YAML file "
                      "({\"reduction\": [...]} or {\"actuator_from_joint\": [[...], ...]}); empty: none");
  }
  // Sequential design (--given): logs the robot already has, comma-separated.
  auto set_given = [this](const std::string& text) {
    given_text = text;
    session.design.given = SplitPaths(text);
  };
  if (ImGui::InputText("given logs##design.given", &given_text)) set_given(given_text);
  widgets.Record("design.given", [set_given](const std::string& text, std::string*) {
    set_given(text);
    return true;
  });
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Logs the robot already has (read with the default columns), or designed trajectories, "
                      "comma-separated: the criterion is that of their union with the new motion; empty: none");
  }
  ImGui::InputText("base pose##design.base_pose", &base_pose_text);
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    std::string why;
    design_text_error = ParseBasePose(base_pose_text, &d.design.base_pose, &why) ? "" : "design.base_pose: " + why;
  }
  widgets.Record("design.base_pose", [this](const std::string& text, std::string* why) {
    if (!ParseBasePose(text, &session.design.design.base_pose, why)) return false;
    base_pose_text = text;
    return true;
  });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("x,y,z [m], roll,pitch,yaw [rad] of the robot's base in the world (gravity along its -z)");
  ImGui::PopItemWidth();
}

// The limits file (DesignCommandOptions::limits) fills the joint table (the
// robot file's limits where it omits one), which the design keeps; its
// "actuators" are read when the design starts (Session::StartDesign). A bad
// file is named with its field in the messages and leaves the table.
void GuiApp::Impl::ReadDesignLimitsFile() {
  if (session.design.limits.empty()) return;
  try {
    session.limits = ReadLimitsFile(session.design.limits, session.model());
  } catch (const std::exception& e) {
    session.Error(std::string("design.limits: ") + e.what());
  }
}

void GuiApp::Impl::DrawDesignTab() {
  DesignCommandOptions& d = session.design;
  const bool running = session.running(JobKind::kDesign);
  ImGui::BeginDisabled(running);
  ImGui::PushItemWidth(110);
  ImGui::TextColored(kDimColor, "Fourier series, one period of 1/f0");
  widgets.InputInt("design.harmonics", "harmonics", &d.design.harmonics, 1, 20);
  ImGui::SameLine(260);
  widgets.InputDouble("design.f0", "f0 [Hz]", &d.design.f0);
  widgets.InputInt("design.samples", "samples", &d.design.samples, 4, 100000);
  ImGui::SameLine(260);
  widgets.InputDouble("design.margin", "margin", &d.design.margin);
  widgets.Checkbox("design.rest_to_rest", "rest to rest", &d.design.rest_to_rest);
  widgets.Combo("design.model", "model", &d.model, kIdentificationModelNames);
  ImGui::SameLine(260);
  widgets.Combo("design.criterion", "criterion", &d.criterion, kDesignCriterionNames);
  widgets.Combo("design.algorithm", "algorithm", &d.algorithm, kDesignAlgorithmNames);
  ImGui::SameLine(260);
  widgets.InputInt("design.starts", "starts", &d.design.starts, 1, 64);
  widgets.InputUnsigned("design.seed", "seed", &d.design.seed);
  ImGui::SameLine(260);
  widgets.InputInt("design.max_evaluations", "evaluations", &d.design.max_evaluations, 1, 1000000);
  widgets.InputInt("design.threads", "threads", &d.design.threads, 1, 64);
  ImGui::SameLine(260);
  widgets.InputDouble("design.clearance", "clearance [m]", &d.design.clearance);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();

  if (!design_text_error.empty()) ImGui::TextColored(kErrorColor, "%s", design_text_error.c_str());
  if (widgets.Button("design.run", "Run design", !running)) session.StartDesign();
  ImGui::SameLine();
  if (widgets.Button("design.stop", "Stop", running)) session.StopDesign();
  const std::vector<double> curve = session.DesignCurve();
  if (running) {
    ImGui::SameLine();
    ImGui::Text("running: %zu progress reports%s", curve.size(), curve.empty() ? ", nothing feasible yet" : "");
  }
  // Under the buttons, which stay in view in a small window.
  ImGui::BeginDisabled(running);
  DrawDesignCell();
  ImGui::EndDisabled();

  // Live curve of the best criterion over all starts.
  std::vector<float> values(curve.begin(), curve.end());
  if (values.size() == 1) values.push_back(values.front());  // a line needs two points
  std::string overlay = curve.empty() ? "best criterion (none yet)" : "best criterion " + Number(curve.back());
  ImGui::PlotLines("##curve", values.empty() ? nullptr : values.data(), static_cast<int>(values.size()), 0,
                   overlay.c_str(), FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 90));
  widgets.Record("design.curve");

  const auto& report = session.design_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "No design yet.");
    return;
  }
  const DesignResult& r = report->result;
  if (ImGui::BeginTable("design_result", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchSame)) {
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("initial");
    ImGui::TableSetupColumn("designed");
    ImGui::TableHeadersRow();
    auto row = [](const char* name, double a, double b) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(name);
      ImGui::TableSetColumnIndex(1);
      TextCell(Number(a));
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(b));
    };
    row("criterion", r.initial_value, r.value);
    row("cond(W)", r.initial.cond, r.final.cond);
    row("normalised cond", r.initial.cond_normalised, r.final.cond_normalised);
    row("log det(WᵀW/m)", r.initial.log_det, r.final.log_det);
    row("σ_min(W)", r.initial.sigma_min, r.final.sigma_min);
    ImGui::EndTable();
  }
  ImGui::Text("%d evaluations in %.2f s; %s at %g Hz%s", r.evaluations, r.wall_seconds,
              r.check.feasible() ? "feasible" : "INFEASIBLE", r.check.rate_hz, r.stopped ? " (stopped)" : "");
  if (!r.check.feasible()) ImGui::TextColored(kErrorColor, "%s", r.check.Explain().c_str());

  // Per-constraint margins, tightest first.
  std::vector<ConstraintMargin> margins = r.check.margins;
  auto relative = [](const ConstraintMargin& m) { return m.limit > 0 ? m.margin / m.limit : m.margin; };
  std::sort(margins.begin(), margins.end(),
            [&](const ConstraintMargin& a, const ConstraintMargin& b) { return relative(a) < relative(b); });
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingStretchSame;
  if (ImGui::BeginTable("margins", 6, flags, ImVec2(0, std::max(60.0f, ImGui::GetContentRegionAvail().y)))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* c : {"joint", "limit on", "t [s]", "value", "limit", "margin"}) ImGui::TableSetupColumn(c);  // clearance: the pair
    ImGui::TableHeadersRow();
    for (const ConstraintMargin& m : margins) {
      ImGui::TableNextRow();
      const ImVec4* color = m.margin < 0 ? &kErrorColor : nullptr;
      ImGui::TableSetColumnIndex(0);
      TextCell(m.quantity == "clearance" ? m.pair : std::to_string(m.joint + 1), color);
      ImGui::TableSetColumnIndex(1);
      TextCell(m.quantity, color);
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(m.time, "%.3f"), color);
      ImGui::TableSetColumnIndex(3);
      TextCell(Number(m.value), color);
      ImGui::TableSetColumnIndex(4);
      TextCell(Number(m.limit), color);
      ImGui::TableSetColumnIndex(5);
      TextCell(Number(m.margin), color);
    }
    ImGui::EndTable();
  }
}

}  // namespace idbench::gui
