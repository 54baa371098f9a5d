// The workbench window's content: a 3D viewport with a timeline, and the
// robot, design, experiment, compare and export panels over one Session. The
// same code draws in a GLFW window and headless (OSMesa); the platform layer
// (gui_window.cc, headless_gui.cc) owns the GL context, ImGui's context and its renderer,
// feeds input, and calls Frame between ImGui::NewFrame and ImGui::Render.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/gui/session.h"
#include "idbench/gui/widget_registry.h"
#include "idbench/render/gl_proc_loader.h"

namespace idbench::gui {

// Layout of the window (fractions of its size): the viewport and robot panel
// on the left, the tabbed panels and the messages on the right.
struct GuiLayout {
  float left_fraction = 0.52f;      // width of the left column
  float viewport_fraction = 0.60f;  // height of the viewport in the left column
  float messages_height = 120.0f;   // [px] at the bottom right
};

class GuiApp {
 public:
  // A GL 3.3 context must be current (the viewport's renderer loads through
  // `loader`) and an ImGui context must exist. Throws std::runtime_error when
  // the renderer cannot be created.
  GuiApp(const SessionOptions& options, GlProcLoader loader);
  ~GuiApp();
  GuiApp(const GuiApp&) = delete;
  GuiApp& operator=(const GuiApp&) = delete;

  // Builds every panel for one frame of dt_seconds (the timeline advances by
  // it when playing) and draws the 3D view into the renderer's texture.
  void Frame(double dt_seconds);

  Session& session();
  const WidgetRegistry& widgets() const;
  GuiLayout& layout();

  // Timeline: the shown instant [s] of the current motion, or of the log
  // while the Log tab is open (the view replays it), and the q drawn there.
  double time() const;
  bool playing() const;
  Eigen::VectorXd shown_q() const;
  // What the robot panel's combo shows: the loaded built-in's name, or
  // "(URDF file)" when the robot came from a URDF.
  const std::string& robot_combo() const;

  // A screenshot the Export panel asked for: its path, once.
  std::optional<std::string> TakeScreenshotRequest();
  // Files dropped onto the window, routed by RouteDroppedFiles
  // (dropped_files.h): a .urdf (or .xacro) is loaded as the robot, a log
  // becomes the Log tab's log (of two dropped together the second is the
  // held-out one; with `held_out`, Shift held, and a log set, the held-out
  // one); anything else, or a drop while a job runs, is a message.
  void DropFiles(const std::vector<std::string>& paths, bool held_out = false);
  // Blocks until the Log tab's plot has read its log, if a read is in flight
  // (it runs off the UI thread): headless frames start with it, so that a
  // script sees the plot in the frame after the log was chosen.
  void WaitForLogPlot();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace idbench::gui
