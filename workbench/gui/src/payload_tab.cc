// The Payload tab (`idbench payload`): an identified robot's URDF, a log with
// the payload and optionally an unloaded one of the same motion, the link
// carrying it and the robot's friction terms; Estimate runs RunPayload on
// session.payload (the command line's options struct, so the same numbers)
// on a worker thread (the logs read with the Log tab's options, the robot at
// the Design tab's base pose: one set of log-reading options), then shows
// the mass, centre of mass and inertia with σ and each quantity's status (the
// ones the motion does not determine as "not identifiable", never as
// numbers) and the verdict. Export writes
// payload.json and payload.urdf.xml through the library's PayloadFiles.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/engine/robot_library.h"

namespace idbench::gui {
namespace {

const ImVec4 kVerdictGoodColor(0.10f, 0.55f, 0.20f, 1.0f);

// "viscous, coulomb" -> {"viscous", "coulomb"}: the terms ParseFrictionTerms accepts.
bool ParsePayloadFriction(const std::string& text, std::vector<std::string>* terms, std::string* why) {
  std::vector<std::string> parsed;
  std::istringstream in(text);
  for (std::string term; std::getline(in, term, ',');) {
    term.erase(0, term.find_first_not_of(" \t"));
    term.erase(term.find_last_not_of(" \t") + 1);
    if (!term.empty()) parsed.push_back(term);
  }
  if (!ParseFrictionTerms(parsed, why)) return false;
  *terms = parsed;
  return true;
}

// The link names of a robot (a built-in name or a URDF file), or none when it
// cannot be read (running the estimate then says why).
std::vector<std::string> LinkNamesOf(const std::string& robot) {
  const std::vector<std::string> builtins = BuiltinRobotNames();
  std::error_code error;
  if (std::find(builtins.begin(), builtins.end(), robot) == builtins.end() &&
      !std::filesystem::is_regular_file(robot, error))
    return {};
  try {
    const RobotModel model = idbench::LoadRobot(robot).model;
    std::vector<std::string> names;
    for (const Link& link : model.links()) names.push_back(link.name);
    return names;
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace

void GuiApp::Impl::DrawPayloadTab() {
  PayloadOptions& p = session.payload;
  const bool running = session.running(JobKind::kPayload);
  if (!payload_fields_initialised) {
    for (const std::string& term : p.friction) payload_friction_text += (payload_friction_text.empty() ? "" : ",") + term;
    payload_fields_initialised = true;
  }
  ImGui::BeginDisabled(running);
  ImGui::PushItemWidth(-150);
  widgets.InputText("payload.robot", "identified robot", &p.robot);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("URDF file (identify's identified.urdf) or built-in name");
  widgets.InputText("payload.data", "log with payload", &p.loaded_log);
  widgets.InputText("payload.unloaded", "unloaded log", &p.unloaded_log);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Optional: the same motion without the payload; cancels the robot file's errors");
  // The link: a combo of the robot's links once the robot is readable, else its name.
  if (p.robot != payload_links_robot) {
    payload_links_robot = p.robot;
    payload_links = LinkNamesOf(p.robot);
  }
  if (payload_links.empty()) {
    widgets.InputText("payload.link", "link", &p.payload_link);
  } else {
    std::vector<std::string> options{""};  // "(default)": the chain's last link
    options.insert(options.end(), payload_links.begin(), payload_links.end());
    widgets.Combo("payload.link", "link", &p.payload_link, options);
  }
  ImGui::InputText("friction (two logs)##payload.friction", &payload_friction_text);
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    std::string why;
    payload_text_error = ParsePayloadFriction(payload_friction_text, &p.friction, &why) ? "" : "payload.friction: " + why;
  }
  widgets.Record("payload.friction", [this, &p](const std::string& text, std::string* why) {
    if (!ParsePayloadFriction(text, &p.friction, why)) return false;
    payload_friction_text = text;
    return true;
  });
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The robot's joint terms estimated with it from two logs, of: none, viscous, coulomb, offset, rotor");
  ImGui::PopItemWidth();
  ImGui::SetNextItemWidth(90);
  widgets.InputDouble("payload.max_relative_sigma", "max relative σ", &p.max_relative_sigma);
  ImGui::SameLine();
  widgets.Checkbox("payload.write_unverified", "write URDF unverified", &p.write_unverified);
  ImGui::EndDisabled();
  if (JobButton("payload.run", "Estimate payload", !running && !p.loaded_log.empty() && !p.robot.empty(), running,
                "estimating..."))
    session.StartPayload();
  if (!payload_text_error.empty()) ImGui::TextColored(kErrorColor, "%s", payload_text_error.c_str());
  ImGui::TextColored(kDimColor, "logs read with the Log tab's columns, angle unit and drive gains; "
                                "the robot mounted at the Design tab's base pose");
  ImGui::Separator();
  DrawPayloadResults();
}

// The quantities with σ and status, why some are not identifiable, the
// verdict, and the export.
void GuiApp::Impl::DrawPayloadResults() {
  const auto& summary = session.payload_summary();
  if (!summary) {
    ImGui::TextColored(kDimColor, "No payload estimated yet.");
    return;
  }
  const PayloadEstimate& e = summary->estimate;
  const PayloadOptions& options = session.payload_estimated_with();
  ImGui::Text("Link '%s', %d samples%s: rank %d, residual RMS %.3g N m", summary->link_name.c_str(),
              summary->n_loaded, e.two_logs ? (" and " + std::to_string(summary->n_unloaded) + " unloaded").c_str()
                                            : ", the robot file's model subtracted",
              e.rank, e.residual_rms);
  const std::vector<PayloadRow> rows = session.PayloadRows();
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("payload_quantities", 5, flags)) {
    for (const char* c : {"quantity", "estimate", "σ", "unit", "status"}) ImGui::TableSetupColumn(c);
    ImGui::TableHeadersRow();
    for (const PayloadRow& row : rows) {
      const ImVec4* color = row.status == "not identifiable"    ? &kErrorColor
                            : row.status == "poorly determined" ? &kErrorColor
                                                                : nullptr;
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      TextCell(row.name, color);
      ImGui::TableSetColumnIndex(1);
      TextCell(row.value_text, color);
      if (!row.reason.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.reason.c_str());
      ImGui::TableSetColumnIndex(2);
      TextCell(row.sigma_text, color);
      ImGui::TableSetColumnIndex(3);
      TextCell(row.unit, color);
      ImGui::TableSetColumnIndex(4);
      TextCell(row.status, color);
    }
    ImGui::EndTable();
  }
  widgets.Record("payload.table");
  ImGui::TextColored(kDimColor, "centre of mass in link '%s' frame; inertia about the centre of mass, in its axes",
                     summary->link_name.c_str());
  // The verdict decides whether payload.urdf.xml is written.
  ImGui::TextColored(summary->good() ? kVerdictGoodColor : kErrorColor, "verdict: %s",
                     PayloadStatusName(summary->status));
  if (!summary->message.empty()) {
    ImGui::SameLine();
    ImGui::TextWrapped("%s", summary->message.c_str());
  }
  widgets.Record("payload.verdict");
  ImGui::SetNextItemWidth(-220);
  widgets.InputText("payload.out_dir", "export folder", &session.payload.out_dir);
  ImGui::SameLine();
  if (widgets.Button("payload.export", WritesPayloadUrdf(options, *summary) ? "Export" : "Export (json only)"))
    session.ExportPayload();
}

}  // namespace idbench::gui
