// The named widgets of the last frame: where each was drawn and how to set
// the value it edits. Panels record every widget a script may use; a script
// (headless mode) clicks a widget by moving the mouse to its rectangle and
// pressing the button, or sets a value through the widget's setter, which
// writes the same variable the widget edits. No ImGui here.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace idbench::gui {

struct WidgetRect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [px], window coordinates, y down
  float center_x() const { return 0.5f * (x0 + x1); }
  float center_y() const { return 0.5f * (y0 + y1); }
  float width() const { return x1 - x0; }
  float height() const { return y1 - y0; }
};

// Parses text into the widget's variable; returns false with *why set when
// the text is not a valid value (the variable is then unchanged).
using WidgetSetter = std::function<bool(const std::string& text, std::string* why)>;

struct WidgetEntry {
  WidgetRect rect;
  bool visible = false;  // inside its window's visible area
  WidgetSetter setter;   // null for buttons, tabs, plots
};

class WidgetRegistry {
 public:
  // Starts a frame's list; EndFrame makes it the last complete frame's.
  void BeginFrame();
  void EndFrame();
  // Records a widget of the current frame (a later record of the name wins).
  void Record(const std::string& name, const WidgetRect& rect, bool visible, WidgetSetter setter = nullptr);

  // The widget as drawn in the last complete frame, or null.
  const WidgetEntry* Find(const std::string& name) const;
  // Names of the last complete frame, sorted (for messages).
  std::vector<std::string> Names() const;

 private:
  std::map<std::string, WidgetEntry> drawing_;  // this frame so far
  std::map<std::string, WidgetEntry> last_;     // last complete frame
};

}  // namespace idbench::gui
