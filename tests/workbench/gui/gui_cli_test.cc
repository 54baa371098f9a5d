// `idbench gui` as a user runs it: headless with a script, and the real
// window (GLFW + OpenGL 3 through glfwGetProcAddress) under a virtual X
// server, skipped where Xvfb is not installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "idbench/render/png_codec.h"
#include "render/image_test_util.h"

namespace {

namespace fs = std::filesystem;

bool OnPath(const std::string& program) {
  return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
}

idbench::Image ReadPng(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return idbench::DecodePng(bytes.str());
}

TEST(GuiCliTest, HeadlessScriptWritesScreenshotsAndExports) {
  const char* idbench = std::getenv("IDBENCH");
  ASSERT_NE(idbench, nullptr);
  const fs::path dir = fs::temp_directory_path() / ("idbench_gui_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "script.txt") << "# play a little, then export\nclick timeline.play\nframes 30\n"
                                       "click tab.export\nclick export.trajectory_csv\n"
                                       "screenshot " << (dir / "mid.png").string() << "\n";
  const std::string command = "LP_NUM_THREADS=1 " + std::string(idbench) + " gui --headless --size 960x600 --script " +
                              (dir / "script.txt").string() + " --screenshot " + (dir / "last.png").string() +
                              " --out " + (dir / "out").string() + " > " + (dir / "stdout.txt").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const idbench::Image last = ReadPng(dir / "last.png");
  EXPECT_EQ(last.width, 960);
  EXPECT_EQ(last.height, 600);
  EXPECT_GT(idbench::testing::RobotBox(last, 0, 0, 480, 340).count, 2000);
  EXPECT_TRUE(fs::is_regular_file(dir / "mid.png"));
  // The paper motion (10 s at 1 kHz) exported as the trajectory CSV.
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "trajectory.csv"));

  // A bad step: exit 1, the line named on stderr.
  std::ofstream(dir / "bad.txt") << "frames 1\nset design.f0 fast\n";
  const std::string bad = "LP_NUM_THREADS=1 " + std::string(idbench) + " gui --headless --script " +
                          (dir / "bad.txt").string() + " --out " + (dir / "out").string() + " > /dev/null 2> " +
                          (dir / "stderr.txt").string();
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 1);
  std::ifstream err(dir / "stderr.txt");
  std::string line;
  std::getline(err, line);
  EXPECT_EQ(line, "idbench gui: " + (dir / "bad.txt").string() + ":2: design.f0: expected a number, got 'fast'");
  fs::remove_all(dir);
}

TEST(GuiCliTest, OpensTheWindowUnderXvfb) {
  if (!OnPath("xvfb-run") || !OnPath("Xvfb"))
    GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb); the windowed GUI is not tested here";
  const char* idbench = std::getenv("IDBENCH");
  ASSERT_NE(idbench, nullptr);
  const fs::path dir = fs::temp_directory_path() / ("idbench_gui_window_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path shot = dir / "window.png";
  const std::string command = "xvfb-run -a -s '-screen 0 1280x720x24' " + std::string(idbench) +
                              " gui --robot paper6r --frames 5 --screenshot " + shot.string() + " --out " +
                              (dir / "out").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const idbench::Image image = ReadPng(shot);
  EXPECT_EQ(image.width, 1280);
  EXPECT_EQ(image.height, 720);
  // The robot in the viewport (top left).
  EXPECT_GT(idbench::testing::RobotBox(image, 0, 0, 600, 400).count, 2000);
  fs::remove_all(dir);
}

}  // namespace
