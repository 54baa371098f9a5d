// `idbench render`, and the figure of `idbench run`, run as a user would.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "idbench/render/png_codec.h"
#include "render/image_test_util.h"
#include "workbench/cli/rendering_cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using idbench::Image;
using idbench::testing::PixelBox;
using idbench::testing::Result;
using idbench::testing::RobotBox;
using idbench::testing::Slurp;

class RenderCliTest : public idbench::testing::RenderingCliFixture {
 protected:
  static Image ReadPng(const fs::path& path) { return idbench::DecodePng(Slurp(path)); }

  // Every panel of a columns × rows figure shows the robot clear of its edges,
  // covering at least min_fraction of the panel.
  static void ExpectRobotInEveryPanel(const Image& figure, int columns, int rows, double min_fraction = 0.03) {
    const int w = figure.width / columns, h = figure.height / rows;
    for (int k = 0; k < columns * rows; ++k) {
      const int x = (k % columns) * w, y = (k / columns) * h;
      const PixelBox box = RobotBox(figure, x, y, w, h);
      EXPECT_GT(box.count, min_fraction * w * h) << "panel " << k;
      EXPECT_GT(box.x0, x + 1) << "panel " << k;
      EXPECT_GT(box.y0, y + 1) << "panel " << k;
      EXPECT_LT(box.x1, x + w - 2) << "panel " << k;
      EXPECT_LT(box.y1, y + h - 2) << "panel " << k;
    }
  }

  // Nothing but `expected` files in the directory (no temporaries left).
  void ExpectOnlyFiles(const fs::path& dir, std::vector<std::string> expected) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir)) found.push_back(entry.path().filename().string());
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(found, expected);
  }
};

TEST_F(RenderCliTest, DefaultFigureIsThePapersEightPanelsAndByteIdenticalAcrossRuns) {
  const Result first = Run("render --out " + (dir_ / "a.png").string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("8 instants (1920x720 px)"), std::string::npos) << first.out;
  const Result second = Run("render --out " + (dir_ / "b.png").string());
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(Slurp(dir_ / "a.png"), Slurp(dir_ / "b.png"));
  const Image figure = ReadPng(dir_ / "a.png");
  ASSERT_EQ(figure.width, 4 * 480);
  ASSERT_EQ(figure.height, 2 * 360);
  ExpectRobotInEveryPanel(figure, 4, 2);
}

TEST_F(RenderCliTest, StripOfChosenInstantsAndSize) {
  const Result r = Run("render --robot puma560 --trajectory general --duration 4 --times 0,0.5,1.2 --layout strip "
                       "--size 200x150 --out " + (dir_ / "sub" / "puma.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image figure = ReadPng(dir_ / "sub" / "puma.png");
  EXPECT_EQ(figure.width, 600);
  EXPECT_EQ(figure.height, 150);
  ExpectRobotInEveryPanel(figure, 3, 1, 0.01);  // the PUMA's links are thin (4 cm)
}

// A trajectory file of 5 s (its last sample at 4.999 s) is shown whole by
// default (6ab1a0b: 0–2 s): the same figure as the eight instants
// 0.15·k·4.999 s, k = 0…7, to 3 digits, the last one clamped to the end,
// given by hand.
TEST_F(RenderCliTest, TrajectoryFileIsShownWholeByDefault) {
  const fs::path motion = dir_ / "motion.csv";
  ASSERT_EQ(Run("simulate --duration 5 --out " + motion.string()).exit_code, 0);
  const Result r = Run("render --trajectory " + motion.string() + " --size 120x90 --out " + (dir_ / "a.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("8 instants"), std::string::npos) << r.out;
  const Result given = Run("render --trajectory " + motion.string() + " --times 0,0.75,1.5,2.25,3,3.75,4.5,4.999 " +
                           "--size 120x90 --out " + (dir_ / "b.png").string());
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_EQ(Slurp(dir_ / "a.png"), Slurp(dir_ / "b.png"));
}

TEST_F(RenderCliTest, BadInputIsOneMessageAndWritesNothing) {
  const fs::path out = dir_ / "fig.png";
  {
    std::ofstream previous(out);
    previous << "previous";
  }
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const Case cases[] = {
      {"--times 0,3", 2, "--times: time 3 s is outside the trajectory [0, 2] s"},
      {"--times -0.5", 2, "--times: time -0.5 s is outside the trajectory [0, 2] s"},
      {"--times inf", 2, "--times: expected finite times [s], got inf"},  // not "outside [0, inf]"
      {"--size 0x0", 2, "--size: panels must be 32..4096 px per side, got 0x0"},
      {"--size 100000x360", 2, "--size: panels must be 32..4096 px per side, got 100000x360"},
      {"--size 4000x4000", 2, "--size: the figure would have 128000000 pixels"},
      {"--size big", 2, "--size: expected WxH in pixels"},
      {"--layout diagonal", 2, "--layout: expected 'grid' or 'strip', got 'diagonal'"},
      {"--accel 0", 2, "--accel: must be > 0 deg/s^2, got 0"},
      {"--duration -1", 2, "--duration: must be > 0 s, got -1"},
      {"--base-pose 0,0,1", 2, "--base-pose"},
      {"--scene " + (dir_ / "nowhere.json").string(), 2, "nowhere.json"},
      {"--trajectory nowhere.json", 2, "nowhere.json"},  // a wrong input: exit 2
  };
  for (const Case& c : cases) {
    const Result r = Run("render " + c.args + " --out " + out.string());
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
    EXPECT_EQ(Slurp(out), "previous") << c.args;
  }
  // A directory, and a path under a regular file.
  Result r = Run("render --out " + dir_.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  r = Run("render --out " + (out / "x.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
  ExpectOnlyFiles(dir_, {"fig.png", "stderr", "stdout"});
}

// The cell and the mounting: a big box in front of the robot, beside it, is drawn (the figure
// changes, and pixels of the box's sand colour appear); a ceiling-mounted
// robot (base 2.5 m up, turned over) is drawn hanging from its base: the
// first link (blue, the base's) moves from below the robot's pixel centroid
// to above it.
TEST_F(RenderCliTest, SceneAndBasePoseAreDrawn) {
  const fs::path scene = dir_ / "scene.json";
  std::ofstream(scene) << R"({"obstacles": [{"type": "box", "size": [0.6, 0.6, 1.2], "pose": [-0.8, -0.8, 0.6, 0, 0, 0]}]})";
  const std::string common = "render --times 0 --size 320x240 --out ";
  ASSERT_EQ(Run(common + (dir_ / "plain.png").string()).exit_code, 0);
  const Result celled = Run(common + (dir_ / "cell.png").string() + " --scene " + scene.string());
  ASSERT_EQ(celled.exit_code, 0) << celled.err;
  const Result ceiling = Run(common + (dir_ / "ceiling.png").string() + " --base-pose 0,0,2.5,3.141592653589793,0,0");
  ASSERT_EQ(ceiling.exit_code, 0) << ceiling.err;
  const Image plain = ReadPng(dir_ / "plain.png"), cell = ReadPng(dir_ / "cell.png");
  // Sand (0.74, 0.69, 0.60) lit: red above green above blue, not grey, not a link colour.
  const auto sand = [](const std::uint8_t* p) { return p[0] > p[1] + 4 && p[1] > p[2] + 8 && p[0] - p[2] < 60; };
  long long sand_plain = 0, sand_cell = 0;
  for (int v = 0; v < plain.height; ++v) {
    for (int u = 0; u < plain.width; ++u) sand_plain += sand(plain.at(u, v)), sand_cell += sand(cell.at(u, v));
  }
  // A few shaded pixels of the orange link pass the test too (61 of 76800).
  EXPECT_LT(sand_plain, 0.005 * plain.width * plain.height);
  EXPECT_GT(sand_cell - sand_plain, 0.03 * plain.width * plain.height);  // 4264 when written
  EXPECT_GT(idbench::testing::FirstLinkBelowCentroid(plain), 10.0);
  EXPECT_LT(idbench::testing::FirstLinkBelowCentroid(ReadPng(dir_ / "ceiling.png")), -10.0);
}

TEST_F(RenderCliTest, RunWritesTheFigureUnlessToldNotTo) {
  Result r = Run("run --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image figure = ReadPng(dir_ / "run" / "figure.png");
  EXPECT_EQ(figure.width, 1920);
  EXPECT_EQ(figure.height, 720);
  ExpectRobotInEveryPanel(figure, 4, 2);
  // The same figure as `idbench render` of the paper's motion.
  ASSERT_EQ(Run("render --out " + (dir_ / "render.png").string()).exit_code, 0);
  EXPECT_EQ(Slurp(dir_ / "run" / "figure.png"), Slurp(dir_ / "render.png"));

  r = Run("run --no-figure --out " + (dir_ / "plain").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectOnlyFiles(dir_ / "plain", {"log.csv", "results.json"});
}

}  // namespace
