#include "idbench/gui/recent_files.h"

#include <algorithm>

namespace idbench::gui {

void AddRecentFile(const std::string& path, std::vector<std::string>* list) {
  if (path.empty()) return;
  list->erase(std::remove(list->begin(), list->end(), path), list->end());
  list->insert(list->begin(), path);
  if (list->size() > kMaxRecentFiles) list->resize(kMaxRecentFiles);
}

const std::vector<std::string>& RecentFiles::Get(const std::string& field) const {
  static const std::vector<std::string> kNone;
  const auto it = by_field.find(field);
  return it == by_field.end() ? kNone : it->second;
}

std::string FormatRecentFilesLines(const RecentFiles& files) {
  std::string text;
  for (const auto& [field, paths] : files.by_field)
    for (const std::string& path : paths) text += field + "=" + path + "\n";
  return text;
}

bool ReadRecentFilesLine(const std::string& line, RecentFiles* files) {
  std::string text = line;
  while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.pop_back();
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) return false;
  std::vector<std::string>& list = files->by_field[text.substr(0, equals)];
  const std::string path = text.substr(equals + 1);
  if (list.size() < kMaxRecentFiles && std::find(list.begin(), list.end(), path) == list.end()) list.push_back(path);
  return true;
}

}  // namespace idbench::gui
