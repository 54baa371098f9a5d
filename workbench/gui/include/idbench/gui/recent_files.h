// The files last used in the GUI's path fields (log.robot, log.data,
// log.validate), newest first, at most kMaxRecentFiles each. Kept in
// imgui.ini beside the window layout as one section:
//
//   [idbench][RecentFiles]
//   log.data=/data/run_2.csv
//   log.data=/data/run_1.csv
//   log.robot=/robots/arm.urdf
//
// Plain text functions here; the ImGui settings handler that reads and
// writes them is internal (recent_files_settings.h).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace idbench::gui {

inline constexpr size_t kMaxRecentFiles = 8;

// Puts `path` first in `list`, removing an earlier copy, and keeps at most
// kMaxRecentFiles. An empty path changes nothing.
void AddRecentFile(const std::string& path, std::vector<std::string>* list);

struct RecentFiles {
  std::map<std::string, std::vector<std::string>> by_field;  // widget name → paths, newest first

  void Add(const std::string& field, const std::string& path) { AddRecentFile(path, &by_field[field]); }
  const std::vector<std::string>& Get(const std::string& field) const;
};

// The section's lines ("field=path\n", each list newest first).
std::string FormatRecentFilesLines(const RecentFiles& files);
// Reads one line of the section: appends the path to its field's list (kept
// oldest last, duplicates and entries past kMaxRecentFiles dropped). False,
// changing nothing, for a line without '=' or with an empty field or path.
bool ReadRecentFilesLine(const std::string& line, RecentFiles* files);

}  // namespace idbench::gui
