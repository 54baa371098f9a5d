// What the GUI tests that drive a HeadlessGui share: a fresh directory per
// test, a file's text, and a GUI script run as a user would type it.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"

namespace idbench::gui {

// An empty directory idbench_<suite>_<name>_<pid> in the system's temporary
// directory (removed first if left over).
inline std::filesystem::path TempDir(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("idbench_" + suite + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The whole file as text ("" when it cannot be read).
inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `script` (gui_script.h) on `gui`; the test fails with the script's
// message when a line fails.
inline void RunScript(HeadlessGui& gui, const std::string& script) {
  std::string why;
  ASSERT_TRUE(RunGuiScript(gui, ParseGuiScript(script, "test script"), "test script", &why)) << why;
}

}  // namespace idbench::gui
