// Small helpers the GUI's panels share: the panels' window flags, the colours
// for errors and dim hints, and text cells for numbers in tables. Internal:
// not installed.
#pragma once

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace idbench::gui {

inline constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                                ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
inline const ImVec4 kErrorColor(0.80f, 0.10f, 0.10f, 1.0f);
inline const ImVec4 kDimColor(0.45f, 0.45f, 0.45f, 1.0f);

// "1.23e+04", "inf" (limits), "-" (NaN).
inline std::string Number(double v, const char* format = "%.4g") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// "0.5,3.5": numbers at full precision, comma-separated (list fields).
inline std::string JoinNumbers(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ",") + Number(v, "%.17g");
  return text;
}

// "a.csv,b.csv" → {"a.csv", "b.csv"}: file paths in a list field, empty items dropped.
inline std::vector<std::string> SplitPaths(const std::string& text) {
  std::vector<std::string> paths;
  for (size_t start = 0; start <= text.size();) {
    const size_t comma = std::min(text.find(',', start), text.size());
    if (comma > start) paths.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return paths;
}

inline void TextCell(const std::string& text, const ImVec4* color = nullptr) {
  if (color) ImGui::TextColored(*color, "%s", text.c_str());
  else ImGui::TextUnformatted(text.c_str());
}

}  // namespace idbench::gui
