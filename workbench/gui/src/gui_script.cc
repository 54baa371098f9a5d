#include "idbench/gui/gui_script.h"

#include <sstream>
#include <stdexcept>

#include "widgets.h"

namespace idbench::gui {
namespace {

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

}  // namespace

std::vector<ScriptStep> ParseGuiScript(const std::string& text, const std::string& source) {
  std::vector<ScriptStep> steps;
  std::istringstream in(text);
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    // A comment starts at a '#' that begins the line or follows a blank, so
    // a path like run#3.csv keeps its '#'.
    size_t comment = raw.find('#');
    while (comment != std::string::npos && comment > 0 && raw[comment - 1] != ' ' && raw[comment - 1] != '\t') {
      comment = raw.find('#', comment + 1);
    }
    const std::string content = Trim(raw.substr(0, comment));
    if (content.empty()) continue;
    auto fail = [&](const std::string& what) {
      throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
    };
    std::istringstream words(content);
    std::string verb, target;
    words >> verb >> target;
    std::string rest;
    std::getline(words, rest);
    rest = Trim(rest);
    ScriptStep step;
    step.line = line;
    step.target = target;
    if (verb == "click") {
      step.kind = ScriptStep::Kind::kClick;
      if (target.empty() || !rest.empty()) fail("expected 'click WIDGET'");
    } else if (verb == "set") {
      step.kind = ScriptStep::Kind::kSet;
      if (target.empty() || rest.empty()) fail("expected 'set WIDGET VALUE'");
      step.value = rest;
    } else if (verb == "wait") {
      step.kind = ScriptStep::Kind::kWait;
      if (!ParseJobName(target)) fail("expected 'wait JOB [SECONDS]' with JOB one of design, simulate, identify, per-body, compare, report, payload, got '" + target + "'");
      step.value = rest.empty() ? "600" : rest;
      double seconds = 0.0;
      std::string why;
      if (!internal::ParseDouble(step.value, &seconds, &why) || !(seconds > 0)) fail("wait: timeout: expected seconds > 0, got '" + step.value + "'");
    } else if (verb == "frames") {
      step.kind = ScriptStep::Kind::kFrames;
      long long n = 0;
      std::string why;
      if (!rest.empty() || !internal::ParseInt(target, 1, 100000, &n, &why)) fail("frames: " + (why.empty() ? "expected 'frames N'" : why));
      step.value = target;
    } else if (verb == "screenshot") {
      step.kind = ScriptStep::Kind::kScreenshot;
      if (target.empty() || !rest.empty()) fail("expected 'screenshot FILE'");
    } else if (verb == "drop" || verb == "shift-drop") {
      // The rest of the line is one path (it may hold spaces).
      step.kind = ScriptStep::Kind::kDrop;
      step.held_out = verb == "shift-drop";
      step.target = Trim(content.substr(verb.size()));
      if (step.target.empty()) fail("expected '" + verb + " PATH'");
    } else if (verb == "drag") {
      step.kind = ScriptStep::Kind::kDrag;
      std::istringstream fractions(rest);
      std::string from, to, extra;
      fractions >> from >> to >> extra;
      double a = 0.0, b = 0.0;
      std::string why;
      if (target.empty() || to.empty() || !extra.empty() || !internal::ParseDouble(from, &a, &why) ||
          !internal::ParseDouble(to, &b, &why) || !(a >= 0.0 && a < 1.0) || !(b >= 0.0 && b <= 1.0))
        fail("expected 'drag WIDGET X0 X1' with fractions of its width, 0 <= X0 < 1 and 0 <= X1 <= 1");
      step.value = from + " " + to;
    } else {
      fail("unknown step '" + verb + "' (click, set, wait, frames, screenshot, drop, shift-drop, drag)");
    }
    steps.push_back(step);
  }
  return steps;
}

bool RunGuiScript(HeadlessGui& gui, const std::vector<ScriptStep>& steps, const std::string& source,
                  std::string* why) {
  for (const ScriptStep& step : steps) {
    std::string problem;
    bool ok = true;
    switch (step.kind) {
      case ScriptStep::Kind::kClick:
        ok = gui.Click(step.target, &problem);
        break;
      case ScriptStep::Kind::kSet:
        ok = gui.Set(step.target, step.value, &problem);
        break;
      case ScriptStep::Kind::kWait:
        ok = gui.WaitForJob(*ParseJobName(step.target), std::stod(step.value), &problem);
        break;
      case ScriptStep::Kind::kFrames:
        for (int k = std::stoi(step.value); k > 0; --k) gui.RenderFrame();
        break;
      case ScriptStep::Kind::kDrop:
        gui.Drop({step.target}, step.held_out);
        break;
      case ScriptStep::Kind::kDrag: {
        std::istringstream fractions(step.value);
        double from = 0.0, to = 0.0;
        fractions >> from >> to;
        ok = gui.Drag(step.target, from, to, &problem);
        break;
      }
      case ScriptStep::Kind::kScreenshot:
        try {
          gui.WriteScreenshot(step.target);
        } catch (const std::exception& e) {
          ok = false;
          problem = e.what();
        }
        break;
    }
    if (!ok) {
      *why = source + ":" + std::to_string(step.line) + ": " + problem;
      return false;
    }
  }
  return true;
}

}  // namespace idbench::gui
