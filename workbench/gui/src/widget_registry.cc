#include "idbench/gui/widget_registry.h"

namespace idbench::gui {

void WidgetRegistry::BeginFrame() { drawing_.clear(); }

void WidgetRegistry::EndFrame() { last_.swap(drawing_); }

void WidgetRegistry::Record(const std::string& name, const WidgetRect& rect, bool visible, WidgetSetter setter) {
  drawing_[name] = WidgetEntry{rect, visible, std::move(setter)};
}

const WidgetEntry* WidgetRegistry::Find(const std::string& name) const {
  auto it = last_.find(name);
  return it == last_.end() ? nullptr : &it->second;
}

std::vector<std::string> WidgetRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, entry] : last_) names.push_back(name);
  return names;
}

}  // namespace idbench::gui
