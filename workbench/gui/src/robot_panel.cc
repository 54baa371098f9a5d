// The robot panel (below the viewport): load a built-in robot or a URDF, and
// the joint table with the current q and the design's editable limits.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <string>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/engine/robot_library.h"

namespace idbench::gui {

void GuiApp::Impl::DrawRobotPanel() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  ImGui::SetNextWindowPos(ImVec2(0, H * layout.viewport_fraction));
  ImGui::SetNextWindowSize(ImVec2(W * layout.left_fraction, H * (1.0f - layout.viewport_fraction)));
  ImGui::Begin("Robot", nullptr, kPanelFlags);
  const RobotModel& model = session.model();
  const bool idle = !session.any_running();

  ImGui::SetNextItemWidth(120);
  widgets.Combo("robot.builtin", "##builtin", &robot_choice, BuiltinRobotNames());
  ImGui::SameLine();
  // Loading replaces the model this frame draws from: done after the panels.
  if (widgets.Button("robot.load_builtin", "Load", idle && robot_choice != kUrdfChoice)) pending_robot = robot_choice;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 110));
  widgets.InputText("robot.urdf", "##urdf", &urdf_path);
  ImGui::SameLine();
  if (widgets.Button("robot.load_urdf", "Open URDF", idle && !urdf_path.empty())) pending_robot = urdf_path;
  ImGui::Text("%s: %d joints, source '%s'", model.name().c_str(), model.n_dof(), session.robot_source().c_str());

  // Joint table: the current q and the design's limits (editable).
  const Eigen::VectorXd q = CurrentQ();
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingStretchSame;
  const float table_height = ImGui::GetContentRegionAvail().y - ImGui::GetFrameHeightWithSpacing() - 4;
  if (ImGui::BeginTable("joints", 7, flags, ImVec2(0, table_height))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("joint", ImGuiTableColumnFlags_WidthFixed, 50.0f);
    ImGui::TableSetupColumn("q [rad]", ImGuiTableColumnFlags_WidthFixed, 60.0f);
    for (const char* c : {"q min [rad]", "q max [rad]", "qd max [rad/s]", "qdd max [rad/s²]", "τ max [N m]"})
      ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (int j = 0; j < model.n_dof() && j < static_cast<int>(session.limits.size()); ++j) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted(model.link(j).joint_name.empty() ? model.link(j).name.c_str()
                                                               : model.link(j).joint_name.c_str());
      ImGui::TableSetColumnIndex(1);
      ImGui::AlignTextToFramePadding();
      ImGui::Text("%.3f", q[j]);
      JointLimits& l = session.limits[static_cast<size_t>(j)];
      double* cells[] = {&l.q_min, &l.q_max, &l.qd_max, &l.qdd_max, &l.tau_max};
      const char* keys[] = {"q_min", "q_max", "qd_max", "qdd_max", "tau_max"};
      for (int c = 0; c < 5; ++c) {
        ImGui::TableSetColumnIndex(2 + c);
        ImGui::SetNextItemWidth(-FLT_MIN);
        widgets.InputDouble("limits." + std::to_string(j + 1) + "." + keys[c], "", cells[c], "%.4g");
      }
    }
    ImGui::EndTable();
  }
  if (widgets.Button("limits.fill", "Fill missing limits")) session.FillMissingLimits();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("q within [%g, %g] rad, qd %g rad/s, qdd %g rad/s²", session.fill_limits.q_min,
                      session.fill_limits.q_max, session.fill_limits.qd_max, session.fill_limits.qdd_max);
  ImGui::SameLine();
  if (widgets.Button("limits.reset", "Robot file's limits")) session.ResetLimits();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "inf = no limit; the design needs finite q, qd, qdd limits");
  ImGui::End();
}

}  // namespace idbench::gui
