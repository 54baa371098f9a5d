// ImGui widgets bound to names: each draws the widget, then records it in the
// WidgetRegistry with a setter writing the same variable, so that a script
// can click it or set its value. Labels show "label"; ids are the names.
#pragma once

#include <string>
#include <vector>

#include "idbench/gui/widget_registry.h"

namespace idbench::gui::internal {

class Widgets {
 public:
  explicit Widgets(WidgetRegistry* registry) : registry_(registry) {}

  // Records the last ImGui item under `name`.
  void Record(const std::string& name, WidgetSetter setter = nullptr);

  bool Button(const std::string& name, const char* label, bool enabled = true);
  bool InputInt(const std::string& name, const char* label, int* value, int min, int max);
  bool InputUnsigned(const std::string& name, const char* label, unsigned* value);
  bool InputDouble(const std::string& name, const char* label, double* value, const char* format = "%g");
  bool InputText(const std::string& name, const char* label, std::string* value);
  bool Checkbox(const std::string& name, const char* label, bool* value);
  // One of `options` ("" shows as "(default)"); the setter accepts only those.
  bool Combo(const std::string& name, const char* label, std::string* value, const std::vector<std::string>& options);

 private:
  WidgetRegistry* registry_;
};

// Parsing for setters (also used by panels with custom widgets).
bool ParseDouble(const std::string& text, double* value, std::string* why);
bool ParseInt(const std::string& text, long long min, long long max, long long* value, std::string* why);

}  // namespace idbench::gui::internal
