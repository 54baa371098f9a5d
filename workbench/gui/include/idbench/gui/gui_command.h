// `idbench gui`: the workbench window (GLFW + OpenGL 3), or the same GUI
// headless (OSMesa) driven by a script, ending with a screenshot.
#pragma once

#include <string>

namespace idbench::gui {

struct GuiCommandOptions {
  std::string robot = "paper6r";   // built-in name or URDF path
  std::string out_dir = "out/gui"; // simulate, compare and export write here
  std::string data;                // a recorded joint log, opened in the Log tab; "" = none
  std::string validate;            // its held-out log; "" = none
  bool headless = false;
  std::string script;              // headless: steps (gui_script.h); "" = none
  std::string screenshot;          // PNG of the last frame; "" = none
  int frames = 0;                  // windowed: close after this many frames (0: when the user closes it)
  int width = 1280;                // [px]
  int height = 720;                // [px]

  // Checks the options alone; *why names the bad one.
  bool IsValid(std::string* why) const;
};

// Runs the GUI until the window closes or the script ends. Returns the exit
// code: 0, or 1 with one line on stderr (no display, a failed script step,
// an unwritable screenshot). Messages of the session go to stdout when
// headless.
int RunGuiCommand(const GuiCommandOptions& options);

// The windowed GUI (gui_window.cc); 1 with a message when no window opens.
int RunGuiWindow(const GuiCommandOptions& options);

}  // namespace idbench::gui
