// GuiApp's state, shared by the files that draw its panels (gui_app.cc for the
// frame, one file per panel). Internal: not installed.
#pragma once

#include <imgui.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "idbench/gui/gui_app.h"
#include "idbench/gui/log_envelope.h"
#include "idbench/gui/recent_files.h"
#include "idbench/gui/session.h"
#include "idbench/gui/widget_registry.h"
#include "idbench/render/camera.h"
#include "idbench/render/robot_scene.h"
#include "idbench/render/scene_renderer.h"
#include "widgets.h"

namespace idbench::gui {

struct GuiApp::Impl {
  Impl(const SessionOptions& options, GlProcLoader loader) : session(options), renderer(loader), widgets(&registry) {}

  Session session;
  SceneRenderer renderer;
  WidgetRegistry registry;
  internal::Widgets widgets;
  GuiLayout layout;

  // Robot panel
  std::string robot_choice;   // the built-in picked in the combo, or kUrdfChoice when a URDF is loaded
  std::string urdf_path;
  static constexpr const char* kUrdfChoice = "(URDF file)";
  // The panel's fields show the robot the session has (a built-in in the
  // combo, a URDF in the path fields).
  void ShowLoadedRobot();
  std::optional<std::string> pending_robot;  // to load at the end of the frame

  // Viewport and timeline. While the Log tab is open and its plot has read
  // the log, the view replays the log (the robot as logged, at the plot's
  // time cursor t); otherwise it plays the current motion from t = 0.
  double t = 0.0;             // [s] on the shown source's time axis
  bool log_tab_open = false;  // the Log tab was drawn last frame
  bool ReplaysLog() const { return log_tab_open && overview.n_samples() >= 2; }
  double TimelineStart() const;  // [s] the shown source's first instant
  double TimelineEnd() const;    // [s] and its last
  std::string fitted_source;     // the source FitView fitted the camera to
  // "log <path>" while the log is replayed, else the motion's name.
  std::string ShownSource() const { return ReplaysLog() ? "log " + overview_key.substr(0, overview_key.find('\n')) : session.motion; }
  bool playing = false;
  double speed = 1.0;
  CameraView view;
  double zoom = 1.0;          // eye distance scale
  Eigen::Vector3d pan_W = Eigen::Vector3d::Zero();  // [m]
  bool show_com = false;      // centres of mass
  bool show_frames = false;   // link frames (x red, y green, z blue), at the hinge points
  double robot_size = 1.0;    // [m] diagonal of the robot's extent over the motion (marker sizes)
  int fitted_motion_version = -1;
  std::vector<Eigen::Vector3d> motion_points_W;  // the robot's extent over the motion
  Floor floor;
  std::string shown_motion_key;
  // What the texture shows (redrawn only when it changes).
  Eigen::VectorXd drawn_q;
  Eigen::Vector3d drawn_eye_W = Eigen::Vector3d::Zero(), drawn_target_W = Eigen::Vector3d::Zero();
  int drawn_w = 0, drawn_h = 0;
  int drawn_overlays = 0;
  bool drawn_once = false;
  // The cell (design.scene, read when edited) and the mounting (design.base_pose) drawn.
  Cell cell;
  bool scene_dirty = false;
  std::array<double, 6> drawn_base_pose{};
  std::string base_pose_text;      // DesignOptions::base_pose as "x,y,z,roll,pitch,yaw"
  std::string given_text;          // DesignCommandOptions::given as "a.csv,b.csv"
  std::string design_text_error;   // why base_pose_text does not parse ("" = it does)
  bool design_fields_initialised = false;

  // Log tab: the text fields behind the option lists (parsed into session.identify).
  std::string log_robot_path;   // URDF to load
  std::string columns_text;     // IdentifyOptions::format.columns, comma-separated; "" = the header's
  std::string friction_text;    // IdentifyOptions::friction, comma-separated
  std::string time_window_text; // IdentifyOptions::time_window, "T0,T1" [s]; "" = the whole log
  std::string drive_gains_text; // IdentifyOptions::format.drive_gains [N m/A], comma-separated
  std::string more_data_text;   // IdentifyOptions::more_data, comma-separated paths
  std::string text_error;       // why a field above does not parse ("" = they do)
  bool log_fields_initialised = false;
  std::string preview_path;     // the log previewed, and its first lines split at commas
  std::vector<std::vector<std::string>> preview_rows;
  bool plot_held_out = false;   // the torque plots show the held-out log
  bool plot_residuals = false;  // the torque plots show measured − predicted
  bool was_identifying = false; // identify ran last frame (its end selects the Torques tab)
  // The log's overview plot (log_overview.cc): joint positions against time,
  // as a min/max envelope per time bucket; a drag on it chooses the time window.
  std::string overview_key;        // the log, robot and columns it was read for
  LogEnvelope overview;            // [rad] per joint; no bucket until a read has finished
  Eigen::MatrixXd overview_mean;   // [rad] its buckets' means (n_buckets × n_dof)
  std::string overview_error;      // why the log cannot be read ("" = it can)
  // Reads the log for the plot off the UI thread (an hour at 1 kHz takes
  // seconds); a change of log, robot or columns stops a read in flight.
  BackgroundJob overview_job;
  // Applies a finished read of the plot's log (wait: blocks until the read
  // in flight, if any, has finished).
  void CollectLogOverview(bool wait);
  // Recent files of the path fields (log.robot, log.data, log.validate), in imgui.ini.
  RecentFiles recent_files;
  std::map<std::string, std::string> recent_noted;  // field → the value last looked at

  // Payload tab
  std::string payload_friction_text;  // PayloadOptions::friction, comma-separated
  std::string payload_text_error;     // why payload_friction_text does not parse ("" = it does)
  bool payload_fields_initialised = false;
  std::string payload_links_robot;    // the robot payload_links were read from
  std::vector<std::string> payload_links;  // its link names (none when unreadable)

  std::optional<std::string> screenshot_request;
  size_t shown_messages = 0;  // the messages panel scrolls to a new one

  // q [rad] shown at the timeline's t: the log's (its plot's bucket means,
  // linear between the buckets' middles) or the motion's.
  Eigen::VectorXd CurrentQ() const { return QAt(t); }
  Eigen::VectorXd QAt(double time) const;

  // A button that starts a job, with what the job is doing beside it while it runs.
  bool JobButton(const std::string& name, const char* label, bool enabled, bool running, const char* doing) {
    const bool pressed = widgets.Button(name, label, enabled);
    if (running) {
      ImGui::SameLine();
      ImGui::TextUnformatted(doing);
    }
    return pressed;
  }

  void SyncMotion();
  void SyncScene();
  void FitView();
  void AddOverlays(const RobotModel& model, const RobotData& data, Scene* scene) const;
  void DrawViewport();
  void DrawRobotPanel();
  void DrawDesignTab();
  void DrawDesignCell();
  void ReadDesignLimitsFile();  // design.limits into the joint table (design_tab.cc)
  void DrawExperimentTab();
  void DrawPerBodyExperiment(bool busy);
  void DrawCompareTab();
  void DrawExportTab();
  void DrawLogTab();
  void DrawLogPreview();
  void DrawLogOverview();
  void DrawLogDataTab();
  void NoteRecentFile(const std::string& field, const std::string& path, bool editing);
  void RecentFilesCombo(const std::string& field, const std::function<void(const std::string&)>& pick);
  void DrawTorquePlots();
  void DrawLogResults();
  void DrawMessages();
  void DrawPayloadTab();
  void DrawPayloadResults();
};

}  // namespace idbench::gui
