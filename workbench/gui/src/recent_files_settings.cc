#include "idbench/gui/recent_files_settings.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <cstring>
#include <string>

namespace idbench::gui {
namespace {

constexpr const char* kTypeName = "idbench";
constexpr const char* kEntryName = "RecentFiles";

void* ReadOpen(ImGuiContext*, ImGuiSettingsHandler* handler, const char* name) {
  return std::strcmp(name, kEntryName) == 0 ? handler->UserData : nullptr;  // other entries are skipped
}

void ReadLine(ImGuiContext*, ImGuiSettingsHandler*, void* entry, const char* line) {
  ReadRecentFilesLine(line, static_cast<RecentFiles*>(entry));  // a malformed line is ignored, as ImGui does
}

void WriteAll(ImGuiContext*, ImGuiSettingsHandler* handler, ImGuiTextBuffer* out) {
  const auto* files = static_cast<const RecentFiles*>(handler->UserData);
  out->appendf("[%s][%s]\n", kTypeName, kEntryName);
  const std::string lines = FormatRecentFilesLines(*files);
  out->append(lines.c_str(), lines.c_str() + lines.size());
  out->append("\n");
}

}  // namespace

void RegisterRecentFilesSettings(RecentFiles* files) {
  if (ImGuiSettingsHandler* existing = ImGui::FindSettingsHandler(kTypeName)) {
    existing->UserData = files;
    return;
  }
  ImGuiSettingsHandler handler;
  handler.TypeName = kTypeName;
  handler.TypeHash = ImHashStr(kTypeName);
  handler.ReadOpenFn = &ReadOpen;
  handler.ReadLineFn = &ReadLine;
  handler.WriteAllFn = &WriteAll;
  handler.UserData = files;
  ImGui::GetCurrentContext()->SettingsHandlers.push_back(handler);
}

void UnregisterRecentFilesSettings() {
  ImVector<ImGuiSettingsHandler>& handlers = ImGui::GetCurrentContext()->SettingsHandlers;
  const ImGuiID hash = ImHashStr(kTypeName);
  for (int k = 0; k < handlers.Size; ++k)
    if (handlers[k].TypeHash == hash) {
      handlers.erase(handlers.Data + k);
      return;
    }
}

void MarkRecentFilesChanged() { ImGui::MarkIniSettingsDirty(); }

}  // namespace idbench::gui
