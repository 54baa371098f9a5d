// ImGui widgets bound to names: each draws the widget, then records it in the
// WidgetRegistry with a setter writing the same variable, so that a script
// can click it or set its value. Labels show "label"; ids are the names.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/enum_names.h"
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
  // One of an enum's values, shown and set by their names (enum_names.h).
  template <typename Enum, std::size_t N>
  bool Combo(const std::string& name, const char* label, Enum* value, const EnumNames<Enum, N>& names) {
    const int current = static_cast<int>(*value);
    return ComboIndex(name, label, current, std::string(names.Name(*value)), names.Names(),
                      [value](int i) { *value = static_cast<Enum>(i); });
  }
  // The same with "(default)" (nullopt) first.
  template <typename Enum, std::size_t N>
  bool Combo(const std::string& name, const char* label, std::optional<Enum>* value, const EnumNames<Enum, N>& names) {
    std::vector<std::string> options{""};
    for (const std::string& n : names.Names()) options.push_back(n);
    const int current = *value ? 1 + static_cast<int>(**value) : 0;
    return ComboIndex(name, label, current, options[static_cast<std::size_t>(current)], options, [value](int i) {
      if (i == 0) value->reset();
      else *value = static_cast<Enum>(i - 1);
    });
  }
  // One of `options` by index: `current` (-1: none of them) is selected,
  // `value` shown; choose(i) sets the i-th (picked, or set by a script by its text).
  bool ComboIndex(const std::string& name, const char* label, int current, const std::string& value,
                  const std::vector<std::string>& options, const std::function<void(int)>& choose);

 private:
  WidgetRegistry* registry_;
};

// Parsing for setters (also used by panels with custom widgets).
bool ParseDouble(const std::string& text, double* value, std::string* why);
bool ParseInt(const std::string& text, long long min, long long max, long long* value, std::string* why);

}  // namespace idbench::gui::internal
