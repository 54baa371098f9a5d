// `idbench gui` as a user runs it: headless with a script, and the real
// window (GLFW + OpenGL 3 through glfwGetProcAddress) under a virtual X
// server, skipped where Xvfb is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
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

// Every number of two JSON documents equal to 1e-12 relative; keys and strings identical.
void ExpectSameNumbers(const nlohmann::json& a, const nlohmann::json& b, const std::string& at) {
  ASSERT_EQ(a.type(), b.type()) << at;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (const auto& [key, value] : a.items()) {
      ASSERT_TRUE(b.contains(key)) << at << "." << key;
      ExpectSameNumbers(value, b[key], at + "." + key);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (size_t k = 0; k < a.size(); ++k) ExpectSameNumbers(a[k], b[k], at + "[" + std::to_string(k) + "]");
  } else if (a.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), 1e-12 * std::max(std::abs(x), std::abs(y))) << at << ": " << x << " vs " << y;
  } else {
    EXPECT_EQ(a, b) << at;
  }
}

// The Log tab on a real robot's recorded logs (the KUKA LWR4+ of
// ../shared/data/kuka_lwr4, skipped when absent): `idbench gui --robot URDF
// --data measurements_1 --validate measurements_3`, friction
// viscous,coulomb,offset and the pc estimator set by the script, Identify,
// export; the exported identified.json has the numbers `idbench identify`
// writes for the same options, the robot files are beside it, and the
// screenshot shows the torque plots (the predicted torque's orange lines).
TEST(GuiCliTest, LogTabIdentifiesARecordedLogAsTheCommandLine) {
  const fs::path data = fs::path(IDBENCH_SOURCE_DIR) / ".." / "shared" / "data" / "kuka_lwr4";
  if (!fs::exists(data / "logs" / "measurements_1.csv"))
    GTEST_SKIP() << "real-robot data not found at " << data.string()
                 << " (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  const char* idbench = std::getenv("IDBENCH");
  ASSERT_NE(idbench, nullptr);
  const fs::path dir = fs::temp_directory_path() / ("idbench_gui_log_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string urdf = (data / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string();
  const std::string fit = (data / "logs" / "measurements_1.csv").string();
  const std::string held_out = (data / "logs" / "measurements_3.csv").string();
  std::ofstream(dir / "script.txt") << "click tab.log\nset log.friction viscous,coulomb,offset\nset log.estimator pc\n"
                                       "click log.identify\nwait identify 600\nframes 2\n"
                                       "screenshot " << (dir / "log.png").string() << "\n"
                                       "click tab.export\nset export.dir " << (dir / "gui").string() << "\n"
                                       "click export.urdf\n";
  const std::string gui = "LP_NUM_THREADS=1 " + std::string(idbench) + " gui --headless --size 1280x720 --robot " +
                          urdf + " --data " + fit + " --validate " + held_out + " --script " +
                          (dir / "script.txt").string() + " --out " + (dir / "unused").string() + " > " +
                          (dir / "stdout.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(gui.c_str()), 0) << gui;
  const std::string cli = std::string(idbench) + " identify --robot " + urdf + " --data " + fit + " --validate " +
                          held_out + " --friction viscous,coulomb,offset --estimator pc --out " +
                          (dir / "cli").string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cli.c_str()), 0) << cli;

  // The same numbers; only the command line differs (the GUI has none).
  auto read_json = [](const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  };
  nlohmann::json from_gui = read_json(dir / "gui" / "identified.json");
  nlohmann::json from_cli = read_json(dir / "cli" / "identified.json");
  EXPECT_EQ(from_gui["validation"]["data"], held_out);
  from_gui.erase("command");
  from_cli.erase("command");
  ExpectSameNumbers(from_gui, from_cli, "identified.json");
  for (const char* file : {"identified.urdf", "identified.xml", "joints.yaml"}) {
    std::ifstream a(dir / "gui" / file), b(dir / "cli" / file);
    std::stringstream text_a, text_b;
    text_a << a.rdbuf();
    text_b << b.rdbuf();
    EXPECT_FALSE(text_a.str().empty()) << file;
    EXPECT_EQ(text_a.str(), text_b.str()) << file;
  }

  // The torque plots: the predicted torque's orange (255, 150, 40) in the right-hand panel.
  const idbench::Image shot = ReadPng(dir / "log.png");
  int orange = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = shot.width / 2; x < shot.width; ++x) {
      const std::uint8_t* p = shot.at(x, y);
      orange += p[0] > 200 && p[1] > 100 && p[1] < 200 && p[2] < 90 ? 1 : 0;
    }
  EXPECT_GT(orange, 500) << "no torque plot in " << (dir / "log.png").string();
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(GuiCliTest, OpensTheWindowUnderXvfb) {
  if (!OnPath("xvfb-run") || !OnPath("Xvfb"))
    GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb); the windowed GUI is not tested here";
  const char* idbench = std::getenv("IDBENCH");
  ASSERT_NE(idbench, nullptr);
  const fs::path dir = fs::temp_directory_path() / ("idbench_gui_window_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path shot = dir / "window.png";
  // The window keeps its recent files in $XDG_CONFIG_HOME/idbench/imgui.ini:
  // the log given on the command line is the first.
  const fs::path log = dir / "run.csv";
  std::ofstream(log) << "t,q1,q2,q3,q4,q5,q6\n";
  const std::string command = "XDG_CONFIG_HOME=" + (dir / "config").string() + " xvfb-run -a -s '-screen 0 1280x720x24' " +
                              std::string(idbench) + " gui --robot paper6r --frames 5 --screenshot " + shot.string() +
                              " --out " + (dir / "out").string() + " --data " + log.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream ini(dir / "config" / "idbench" / "imgui.ini");
  const std::string ini_text((std::istreambuf_iterator<char>(ini)), std::istreambuf_iterator<char>());
  EXPECT_NE(ini_text.find("[idbench][RecentFiles]\nlog.data=" + log.string() + "\n"), std::string::npos) << ini_text;
  const idbench::Image image = ReadPng(shot);
  EXPECT_EQ(image.width, 1280);
  EXPECT_EQ(image.height, 720);
  // The robot in the viewport (top left).
  EXPECT_GT(idbench::testing::RobotBox(image, 0, 0, 600, 400).count, 2000);
  fs::remove_all(dir);
}

}  // namespace
