#include "idbench/gui/gui_command.h"

#include <cstdio>
#include <exception>

#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"
#include "idbench/workbench/formats/joint_log_csv.h"

namespace idbench::gui {

bool GuiCommandOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (robot.empty()) return fail("--robot: empty");
  if (out_dir.empty()) return fail("--out: empty path");
  if (width < 64 || width > 8192 || height < 64 || height > 8192)
    return fail("--size: expected WxH within [64, 8192] px, got " + std::to_string(width) + "x" + std::to_string(height));
  if (!headless && !script.empty()) return fail("--script needs --headless");
  if (frames < 0) return fail("--frames: must be >= 0, got " + std::to_string(frames));
  return true;
}

int RunGuiCommand(const GuiCommandOptions& options) {
  if (!options.headless) return RunGuiWindow(options);
  try {
    // Read the script first: a bad one fails before any work.
    std::vector<ScriptStep> steps;
    if (!options.script.empty()) steps = ParseGuiScript(ReadTextFile(options.script), options.script);
    HeadlessGui gui({.width = options.width, .height = options.height,
                     .session = {.robot = options.robot, .out_dir = options.out_dir}});
    std::string why;
    const bool ok = RunGuiScript(gui, steps, options.script, &why);
    gui.session().WaitForJobs();
    for (const SessionMessage& m : gui.session().messages())
      std::printf("%s%s\n", m.level == SessionMessage::Level::kError ? "error: " : "", m.text.c_str());
    if (!ok) {
      std::fprintf(stderr, "idbench gui: %s\n", why.c_str());
      return 1;
    }
    if (!options.screenshot.empty()) {
      gui.RenderFrame();
      gui.WriteScreenshot(options.screenshot);
      std::printf("wrote %s\n", options.screenshot.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench gui: %s\n", e.what());
    return 1;
  }
}

}  // namespace idbench::gui
