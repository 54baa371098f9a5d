// The GUI without a display: an OSMesa context, ImGui drawing into an
// offscreen framebuffer of the window's size, and scripted input (a mouse
// that clicks named widgets, setters that type values). What the tests, the
// benchmark and `idbench gui --headless` drive.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "idbench/gui/gui_app.h"
#include "idbench/gui/session.h"
#include "idbench/render/image.h"

namespace idbench::gui {

struct HeadlessGuiOptions {
  int width = 1280;                   // [px]
  int height = 720;                   // [px]
  double frame_seconds = 1.0 / 60.0;  // simulated time per frame (the timeline's clock)
  SessionOptions session;
};

class HeadlessGui {
 public:
  // Creates the context and draws the first frames. Throws std::runtime_error
  // when OSMesa or the renderer cannot start, std::invalid_argument for a
  // size outside [64, 8192].
  explicit HeadlessGui(const HeadlessGuiOptions& options);
  ~HeadlessGui();
  HeadlessGui(const HeadlessGui&) = delete;
  HeadlessGui& operator=(const HeadlessGui&) = delete;

  // One frame with the current input; a screenshot asked for in the Export
  // panel is written after it.
  void RenderFrame();
  // Waits until GL has drawn the last frame (for timing; a read-back waits anyway).
  void Finish();
  // The last frame, read back (top row first).
  Image Screenshot();
  // Screenshot as a PNG file, written atomically. Throws std::runtime_error.
  void WriteScreenshot(const std::string& path);

  // Clicks a widget of the last frame: moves the mouse onto its centre,
  // presses, releases, and draws the result (four frames). False with *why
  // when the widget is unknown or not visible.
  bool Click(const std::string& widget, std::string* why);
  // Sets the value a widget edits (then one frame). False with *why when the
  // widget is unknown, has no value, or the text is not a valid value.
  bool Set(const std::string& widget, const std::string& value, std::string* why);
  // Drops files onto the window (GuiApp::DropFiles, `held_out` for Shift
  // held), then draws the result (two frames: a robot loads at the end of one).
  void Drop(const std::vector<std::string>& paths, bool held_out = false);
  // Drags across a widget of the last frame along its middle: presses at
  // fraction `from` of its width (0 <= from < 1), moves to `to` (0 <= to <= 1),
  // releases, and draws the result. False with *why when the widget is
  // unknown, not visible, or a fraction is outside those ranges.
  bool Drag(const std::string& widget, double from, double to, std::string* why);
  // Renders frames (about 20 per second of wall time, leaving the cores to
  // the job) until the job is no longer running; false on timeout.
  bool WaitForJob(JobKind kind, double timeout_seconds, std::string* why);

  GuiApp& app();
  Session& session() { return app().session(); }
  const WidgetRegistry& widgets() { return app().widgets(); }
  int width() const;
  int height() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace idbench::gui
