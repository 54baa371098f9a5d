#include "idbench/gui/gui_command.h"

#include <cstdio>
#include <exception>

#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/engine/input_file.h"

namespace idbench::gui {

bool GuiCommandOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (robot.empty()) return fail("--robot: empty");
  if (width < 64 || width > 8192 || height < 64 || height > 8192)
    return fail("--size: expected WxH within [64, 8192] px, got " + std::to_string(width) + "x" + std::to_string(height));
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "--out", &out_why)) return fail(out_why);
  if (std::string out_why; !screenshot.empty() && !IsUsableOutputFile(screenshot, "--screenshot", &out_why)) {
    return fail(out_why);
  }
  if (!headless && !script.empty()) return fail("--script needs --headless");
  if (!validate.empty() && data.empty()) return fail("--validate: given without --data");
  if (frames < 0) return fail("--frames: must be >= 0, got " + std::to_string(frames));
  return true;
}

// Exit codes as the command line's (docs/exit-codes.md): 2 for a script or
// option that is wrong (nothing ran), 1 when a step, a job or an export failed.
int RunGuiCommand(const GuiCommandOptions& options) {
  if (!options.headless) return RunGuiWindow(options);
  // Read the script first: a bad one fails before any work.
  std::vector<ScriptStep> steps;
  try {
    if (!options.script.empty()) steps = ParseGuiScript(ReadInputFile(options.script), options.script);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench gui: %s\n", e.what());
    return 2;
  }
  try {
    HeadlessGui gui({.width = options.width, .height = options.height,
                     .session = {.robot = options.robot, .out_dir = options.out_dir}});
    gui.session().identify.data = options.data;  // the Log tab's logs
    gui.session().identify.validate = options.validate;
    std::string why;
    const bool ok = RunGuiScript(gui, steps, options.script, &why);
    gui.session().WaitForJobs();
    int errors = 0;
    for (const SessionMessage& m : gui.session().messages()) {
      const bool error = m.level == SessionMessage::Level::kError;
      errors += error ? 1 : 0;
      std::printf("%s%s\n", error ? "error: " : "", m.text.c_str());
    }
    if (!ok) {
      std::fprintf(stderr, "idbench gui: %s\n", why.c_str());
      return 1;
    }
    if (!options.screenshot.empty()) {
      gui.RenderFrame();
      gui.WriteScreenshot(options.screenshot);
      std::printf("wrote %s\n", options.screenshot.c_str());
    }
    if (errors > 0) {
      std::fprintf(stderr, "idbench gui: %d error%s in the Messages panel (above)\n", errors, errors == 1 ? "" : "s");
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench gui: %s\n", e.what());
    return 1;
  }
}

}  // namespace idbench::gui
