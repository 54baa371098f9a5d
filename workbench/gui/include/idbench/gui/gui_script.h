// Scripts for the headless GUI: one step per line, '#' starts a comment.
//
//   click WIDGET             move the mouse onto a named widget and click it
//   set WIDGET VALUE...      set the value a widget edits (the rest of the line)
//   wait JOB [SECONDS]       render frames until the job (design, simulate,
//                            identify, per-body, compare, report, payload) has
//                            finished; default 600 s
//   frames N                 render N frames (the timeline advances when playing)
//   screenshot FILE          write the window as a PNG
//   drop PATH                drop a file onto the window (the rest of the
//                            line is the path): a URDF, a log, or a message
//   shift-drop PATH          the same with Shift held: a log goes to the
//                            held-out log when a log is set
//   drag WIDGET X0 X1        press at X0, move to X1, release: fractions of
//                            the widget's width (log.overview: the time window)
//
// Widget names are dotted: tab.design, design.harmonics, design.run,
// limits.2.qd_max, experiment.simulate, ... (docs/commands/gui.md lists them).
#pragma once

#include <string>
#include <vector>

#include "idbench/gui/headless_gui.h"

namespace idbench::gui {

struct ScriptStep {
  enum class Kind { kClick, kSet, kWait, kFrames, kScreenshot, kDrop, kDrag };
  Kind kind = Kind::kFrames;
  std::string target;   // widget, job or file
  std::string value;    // set: the value; wait: timeout [s]; frames: count; drag: "X0 X1"
  bool held_out = false;  // drop: Shift held (shift-drop)
  int line = 0;         // 1-based, for messages
};

// Throws std::invalid_argument "source:line: what" for an unknown step, a
// missing argument, an unknown job, or a count that is not a number.
std::vector<ScriptStep> ParseGuiScript(const std::string& text, const std::string& source);

// Runs the steps in order; stops at the first that fails, with *why
// "source:line: what". A job that fails is not a script failure: its message
// is in the session, as a user would see it.
bool RunGuiScript(HeadlessGui& gui, const std::vector<ScriptStep>& steps, const std::string& source,
                  std::string* why);

}  // namespace idbench::gui
