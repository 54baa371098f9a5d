// GuiApp's frame: the viewport and robot panel on the left, the tabs and the
// messages on the right; the panels themselves are drawn in their own files.
#include "idbench/gui/gui_app.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/engine/robot_library.h"
#include "idbench/gui/dropped_files.h"
#include "idbench/gui/recent_files_settings.h"

namespace idbench::gui {

GuiApp::GuiApp(const SessionOptions& options, GlProcLoader loader) : impl_(std::make_unique<Impl>(options, loader)) {
  impl_->ShowLoadedRobot();
  RegisterRecentFilesSettings(&impl_->recent_files);  // read from imgui.ini at the first frame
}

void GuiApp::Impl::ShowLoadedRobot() {
  const std::vector<std::string> names = BuiltinRobotNames();
  const std::string& source = session.robot_source();
  if (std::find(names.begin(), names.end(), source) != names.end()) {
    robot_choice = source;
  } else {
    robot_choice = kUrdfChoice;  // not a built-in: the combo says so, the path fields hold the file
    log_robot_path = urdf_path = source;
  }
}

void GuiApp::WaitForLogPlot() { impl_->CollectLogOverview(true); }

void GuiApp::DropFiles(const std::vector<std::string>& paths, bool held_out) {
  Impl& m = *impl_;
  if (m.session.any_running()) {  // the fields are disabled while a job runs
    m.session.Error("dropped files ignored while a job runs; drop them again when it has finished");
    return;
  }
  for (const DroppedFileRoute& route : RouteDroppedFiles(paths, !m.session.identify.data.empty(), held_out)) {
    switch (route.target) {
      case DroppedFileRoute::Target::kRobot:
        m.log_robot_path = m.urdf_path = route.path;  // the Log tab's and the robot panel's fields
        m.pending_robot = route.path;
        break;
      case DroppedFileRoute::Target::kData:
        m.session.identify.data = route.path;
        break;
      case DroppedFileRoute::Target::kValidate:
        m.session.identify.validate = route.path;
        break;
      case DroppedFileRoute::Target::kNone:
        m.session.Error(route.message);
        continue;
    }
    m.session.Info(route.message);
  }
}

GuiApp::~GuiApp() {
  // The recent files are written with the layout now, while the handler's
  // data exists (ImGui would otherwise save at DestroyContext, after it).
  ImGuiIO& io = ImGui::GetIO();
  if (io.IniFilename && ImGui::GetCurrentContext()->SettingsLoaded) ImGui::SaveIniSettingsToDisk(io.IniFilename);
  io.IniFilename = nullptr;
  UnregisterRecentFilesSettings();
}

void GuiApp::Frame(double dt_seconds) {
  Impl& m = *impl_;
  m.registry.BeginFrame();
  m.session.Poll();
  m.SyncMotion();
  if (m.playing) {
    if (m.ReplaysLog() || m.session.current_motion()) {
      m.t += dt_seconds * m.speed;
      if (m.t > m.TimelineEnd()) m.t = m.TimelineStart();
    } else {
      m.playing = false;
    }
  }

  m.DrawViewport();
  m.DrawRobotPanel();

  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  const float x = W * m.layout.left_fraction;
  ImGui::SetNextWindowPos(ImVec2(x, 0));
  ImGui::SetNextWindowSize(ImVec2(W - x, H - m.layout.messages_height));
  ImGui::Begin("Workbench", nullptr, kPanelFlags);
  if (ImGui::BeginTabBar("tabs")) {
    struct Tab {
      const char* name;
      const char* label;
      void (Impl::*draw)();
    };
    for (const Tab& tab : {Tab{"tab.design", "Design", &Impl::DrawDesignTab},
                           Tab{"tab.experiment", "Experiment", &Impl::DrawExperimentTab},
                           Tab{"tab.log", "Log", &Impl::DrawLogTab},
                           Tab{"tab.compare", "Compare", &Impl::DrawCompareTab},
                           Tab{"tab.payload", "Payload", &Impl::DrawPayloadTab},
                           Tab{"tab.export", "Export", &Impl::DrawExportTab}}) {
      const bool open = ImGui::BeginTabItem(tab.label);
      m.widgets.Record(tab.name);
      if (tab.draw == &Impl::DrawLogTab) {  // the view replays the log from the next frame
        if (open != m.log_tab_open) m.t = 0.0, m.playing = false;
        m.log_tab_open = open;
      }
      if (open) {
        (m.*tab.draw)();
        ImGui::EndTabItem();
      }
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
  m.DrawMessages();
  // The path fields' recent files, once no field is being typed into.
  const bool typing = ImGui::IsAnyItemActive();
  m.NoteRecentFile("log.robot", m.log_robot_path, typing);
  m.NoteRecentFile("log.data", m.session.identify.data, typing);
  m.NoteRecentFile("log.validate", m.session.identify.validate, typing);
  m.registry.EndFrame();
  if (m.pending_robot) {
    if (m.session.LoadRobot(*m.pending_robot)) m.t = 0.0, m.playing = false, m.ShowLoadedRobot();
    m.pending_robot.reset();
  }
}

Session& GuiApp::session() { return impl_->session; }
const WidgetRegistry& GuiApp::widgets() const { return impl_->registry; }
GuiLayout& GuiApp::layout() { return impl_->layout; }
double GuiApp::time() const { return impl_->t; }
bool GuiApp::playing() const { return impl_->playing; }
Eigen::VectorXd GuiApp::shown_q() const { return impl_->CurrentQ(); }
const std::string& GuiApp::robot_combo() const { return impl_->robot_choice; }

std::optional<std::string> GuiApp::TakeScreenshotRequest() {
  std::optional<std::string> request;
  request.swap(impl_->screenshot_request);
  return request;
}

}  // namespace idbench::gui
