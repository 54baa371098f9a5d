// Recent files: newest first, no duplicates, at most kMaxRecentFiles; the
// ini section written and read back through ImGui's settings, beside the
// sections of others.
#include "idbench/gui/recent_files.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "idbench/gui/recent_files_settings.h"

namespace idbench::gui {
namespace {

TEST(RecentFilesTest, NewestFirstWithoutDuplicatesBounded) {
  std::vector<std::string> list;
  AddRecentFile("/a.csv", &list);
  AddRecentFile("/b.csv", &list);
  AddRecentFile("/a.csv", &list);  // used again: first, once
  AddRecentFile("", &list);        // nothing
  EXPECT_EQ(list, (std::vector<std::string>{"/a.csv", "/b.csv"}));
  for (int k = 0; k < 20; ++k) AddRecentFile("/log" + std::to_string(k) + ".csv", &list);
  ASSERT_EQ(list.size(), kMaxRecentFiles);
  EXPECT_EQ(list.front(), "/log19.csv");
  EXPECT_EQ(list.back(), "/log12.csv");
}

TEST(RecentFilesTest, LinesRoundTrip) {
  RecentFiles files;
  files.Add("log.data", "/data/run 1.csv");
  files.Add("log.data", "/data/run=2.csv");  // '=' in a path: the first one splits
  files.Add("log.robot", "/robots/arm.urdf");
  RecentFiles read;
  const std::string text = FormatRecentFilesLines(files);
  size_t start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    EXPECT_TRUE(ReadRecentFilesLine(text.substr(start, end - start), &read));
  EXPECT_EQ(read.by_field, files.by_field);
  EXPECT_EQ(read.Get("log.data"), (std::vector<std::string>{"/data/run=2.csv", "/data/run 1.csv"}));
  EXPECT_TRUE(read.Get("log.validate").empty());
  EXPECT_FALSE(ReadRecentFilesLine("no equals sign", &read));
  EXPECT_FALSE(ReadRecentFilesLine("=/path", &read));
  EXPECT_FALSE(ReadRecentFilesLine("log.data=", &read));
  EXPECT_EQ(read.by_field, files.by_field);
}

// Through ImGui: what SaveIniSettingsToMemory writes, LoadIniSettingsFromMemory
// reads back into another list, with an unrelated section around it.
TEST(RecentFilesTest, ImGuiIniRoundTrip) {
  ImGuiContext* context = ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // nothing on disk
  RecentFiles files;
  for (int k = 0; k < 10; ++k) files.Add("log.data", "/logs/run" + std::to_string(k) + ".csv");
  files.Add("log.validate", "/logs/held out.csv");
  files.Add("log.robot", "/robots/arm.urdf");
  RegisterRecentFilesSettings(&files);
  const std::string ini = std::string("[Window][Debug##Default]\nPos=60,60\nSize=400,400\n\n") +
                          ImGui::SaveIniSettingsToMemory();
  EXPECT_NE(ini.find("[idbench][RecentFiles]\nlog.data=/logs/run9.csv\n"), std::string::npos) << ini;

  RecentFiles read;
  RegisterRecentFilesSettings(&read);  // the handler now fills `read`
  ImGui::LoadIniSettingsFromMemory(ini.c_str(), ini.size());
  EXPECT_EQ(read.by_field, files.by_field);
  ASSERT_EQ(read.Get("log.data").size(), kMaxRecentFiles);
  EXPECT_EQ(read.Get("log.data").front(), "/logs/run9.csv");
  UnregisterRecentFilesSettings();
  EXPECT_EQ(std::string(ImGui::SaveIniSettingsToMemory()).find("idbench"), std::string::npos);
  ImGui::DestroyContext(context);
}

}  // namespace
}  // namespace idbench::gui
