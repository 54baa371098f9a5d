#include "widgets.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace idbench::gui::internal {

bool ParseDouble(const std::string& text, double* value, std::string* why) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || std::isnan(v)) {
    *why = "expected a number, got '" + text + "'";
    return false;
  }
  *value = v;
  return true;
}

bool ParseInt(const std::string& text, long long min, long long max, long long* value, std::string* why) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < min || v > max) {
    *why = "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" + text + "'";
    return false;
  }
  *value = v;
  return true;
}

void Widgets::Record(const std::string& name, WidgetSetter setter) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  registry_->Record(name, WidgetRect{a.x, a.y, b.x, b.y}, ImGui::IsItemVisible(), std::move(setter));
}

bool Widgets::Button(const std::string& name, const char* label, bool enabled) {
  ImGui::BeginDisabled(!enabled);
  const bool pressed = ImGui::Button((std::string(label) + "##" + name).c_str());
  ImGui::EndDisabled();
  Record(name);
  return pressed && enabled;
}

bool Widgets::InputInt(const std::string& name, const char* label, int* value, int min, int max) {
  const bool changed = ImGui::InputInt((std::string(label) + "##" + name).c_str(), value, 1, 10);
  if (changed) *value = std::clamp(*value, min, max);
  Record(name, [value, min, max](const std::string& text, std::string* why) {
    long long v = 0;
    if (!ParseInt(text, min, max, &v, why)) return false;
    *value = static_cast<int>(v);
    return true;
  });
  return changed;
}

bool Widgets::InputUnsigned(const std::string& name, const char* label, unsigned* value) {
  const bool changed = ImGui::InputScalar((std::string(label) + "##" + name).c_str(), ImGuiDataType_U32, value);
  Record(name, [value](const std::string& text, std::string* why) {
    long long v = 0;
    if (!ParseInt(text, 0, 0xffffffffLL, &v, why)) return false;
    *value = static_cast<unsigned>(v);
    return true;
  });
  return changed;
}

bool Widgets::InputDouble(const std::string& name, const char* label, double* value, const char* format) {
  const bool changed = ImGui::InputDouble((std::string(label) + "##" + name).c_str(), value, 0.0, 0.0, format);
  Record(name, [value](const std::string& text, std::string* why) { return ParseDouble(text, value, why); });
  return changed;
}

bool Widgets::InputText(const std::string& name, const char* label, std::string* value) {
  const bool changed = ImGui::InputText((std::string(label) + "##" + name).c_str(), value);
  Record(name, [value](const std::string& text, std::string*) {
    *value = text;
    return true;
  });
  return changed;
}

bool Widgets::Checkbox(const std::string& name, const char* label, bool* value) {
  const bool changed = ImGui::Checkbox((std::string(label) + "##" + name).c_str(), value);
  Record(name, [value](const std::string& text, std::string* why) {
    if (text == "true" || text == "1" || text == "on") *value = true;
    else if (text == "false" || text == "0" || text == "off") *value = false;
    else {
      *why = "expected true or false, got '" + text + "'";
      return false;
    }
    return true;
  });
  return changed;
}

bool Widgets::Combo(const std::string& name, const char* label, std::string* value,
                    const std::vector<std::string>& options) {
  const auto current = std::find(options.begin(), options.end(), *value);
  return ComboIndex(name, label, current == options.end() ? -1 : static_cast<int>(current - options.begin()), *value,
                    options, [value, options](int i) { *value = options[static_cast<size_t>(i)]; });
}

bool Widgets::ComboIndex(const std::string& name, const char* label, int current, const std::string& value,
                         const std::vector<std::string>& options, const std::function<void(int)>& choose) {
  bool changed = false;
  auto shown = [](const std::string& option) { return option.empty() ? "(default)" : option.c_str(); };
  if (ImGui::BeginCombo((std::string(label) + "##" + name).c_str(), shown(value))) {
    for (size_t i = 0; i < options.size(); ++i) {
      const bool selected = static_cast<int>(i) == current;
      if (ImGui::Selectable(shown(options[i]), selected)) {
        changed = !selected;
        choose(static_cast<int>(i));
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  Record(name, [choose, options](const std::string& text, std::string* why) {
    for (size_t i = 0; i < options.size(); ++i) {
      if (options[i] == text) {
        choose(static_cast<int>(i));
        return true;
      }
    }
    *why = "expected one of";
    for (const std::string& option : options) *why += " " + option;
    *why += ", got '" + text + "'";
    return false;
  });
  return changed;
}

}  // namespace idbench::gui::internal
