// The Export tab: the designed trajectory, the shown motion as CSV, the
// identified robot (URDF, MJCF, joints.yaml, identified.json), the report and a screenshot, into the output directory.
#include <imgui.h>

#include "gui_app_impl.h"
#include "gui_helpers.h"

namespace idbench::gui {

void GuiApp::Impl::DrawExportTab() {
  ImGui::SetNextItemWidth(-90);
  widgets.InputText("export.dir", "output dir", &session.out_dir);
  if (widgets.Button("export.trajectory_json", "Trajectory JSON", session.design_report().has_value()))
    session.ExportTrajectoryJson();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "the designed motion's coefficients: trajectory.json");
  if (widgets.Button("export.trajectory_csv", "Trajectory CSV", session.current_motion() != nullptr))
    session.ExportTrajectoryCsv();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "the shown motion at %g Hz: trajectory.csv", session.design.csv_rate_hz);
  if (widgets.Button("export.urdf", "Identified robot", session.identify_report().has_value()))
    session.ExportIdentifiedModel();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "identified.json; physically consistent: identified.urdf, .xml (MJCF), joints.yaml");
  if (JobButton("export.report", "Report", session.identify_report().has_value() && !session.running(JobKind::kReport),
                session.running(JobKind::kReport), "writing the report..."))
    session.StartReport();
  else if (!session.running(JobKind::kReport)) {
    ImGui::SameLine();
    ImGui::TextColored(kDimColor, "the identification's report.html, report.pdf and plots");
  }
  if (widgets.Button("export.screenshot", "Screenshot")) screenshot_request = session.OutPath("screenshot.png");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "this window: screenshot.png");
}

}  // namespace idbench::gui
