// RenderCommand as library calls: the options' figure and their checks (each
// message names its field), the paper's Figure 2 instants scaled to a motion,
// the motion drawn (the paper's: q = ½·qdd·t² on hinges 1 and 2), and the
// image rendered: its size from the options, the robot in every panel, a
// cell's box drawn in its sand colour, the PNG the same pixels, and `run`'s
// figure the same as the paper motion's at the default instants.
#include "idbench/workbench/commands/render_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "idbench/engine/paper6r.h"
#include "idbench/render/png_codec.h"
#include "render/image_test_util.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::PixelBox;
using testing::RobotBox;

TEST(RenderCommandTest, ParseImageSizeReadsTwoPositiveIntegers) {
  int w = 0, h = 0;
  ASSERT_TRUE(ParseImageSize("480x360", &w, &h));
  EXPECT_EQ(w, 480);
  EXPECT_EQ(h, 360);
  ASSERT_TRUE(ParseImageSize("32x4096", &w, &h));
  EXPECT_EQ(w, 32);
  EXPECT_EQ(h, 4096);
  for (const char* bad : {"", "x", "480x", "x360", "480X360", "480 x360", " 480x360", "480x360px", "4.5x3", "480x360x2",
                          "big"}) {
    EXPECT_FALSE(ParseImageSize(bad, &w, &h)) << "'" << bad << "'";
  }
}

// t_k = min(0.15·k·duration, duration), to 3 significant digits: the paper's
// 0, 0.3, …, 1.8, 2 s for 2 s, and the last instant clipped to the motion.
TEST(RenderCommandTest, DefaultFigureTimesScaleThePapersInstants) {
  const std::vector<std::pair<double, std::vector<double>>> cases = {
      {2.0, {0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.0}},
      {10.0, {0.0, 1.5, 3.0, 4.5, 6.0, 7.5, 9.0, 10.0}},
      {1.0, {0.0, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9, 1.0}},
      {0.7, {0.0, 0.105, 0.21, 0.315, 0.42, 0.525, 0.63, 0.7}},  // 0.735 clipped to 0.7
  };
  for (const auto& [duration, expected] : cases) {
    const std::vector<double> times = DefaultFigureTimes(duration);
    ASSERT_EQ(times.size(), expected.size()) << duration;
    for (size_t k = 0; k < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], expected[k]) << duration << " k=" << k;
  }
  // Rounded, so labels read as the paper's, not 0.8999999999999999 s.
  const std::vector<double> paper = DefaultFigureTimes(2.0);
  EXPECT_EQ(PanelLabel(3, paper[3]), "(d) 0.9 s");
  EXPECT_EQ(PanelLabel(7, paper[7]), "(h) 2 s");
}

TEST(RenderCommandTest, FigureCarriesTheOptions) {
  RenderOptions options;
  options.size = "200x150";
  options.layout = "strip";
  options.base_pose.xyz_rpy = {0.1, 0.2, 0.3, 0.0, 0.0, 0.5};
  PoseFigureOptions figure = options.figure(1.0);
  EXPECT_EQ(figure.panel_width, 200);
  EXPECT_EQ(figure.panel_height, 150);
  EXPECT_EQ(figure.layout, "strip");
  EXPECT_EQ(figure.base_pose.xyz_rpy, options.base_pose.xyz_rpy);
  EXPECT_EQ(figure.times, DefaultFigureTimes(1.0));  // none given
  EXPECT_EQ(figure.columns(), 8);
  EXPECT_EQ(figure.rows(), 1);
  EXPECT_TRUE(figure.scene.obstacles.empty());

  options.times = {0.25, 1.75};
  options.size = "big";
  figure = options.figure(1.0);  // times kept even beyond the duration; IsValid against the motion says so
  EXPECT_EQ(figure.times, (std::vector<double>{0.25, 1.75}));
  EXPECT_EQ(figure.panel_width, 0);
  EXPECT_EQ(figure.panel_height, 0);
  EXPECT_FALSE(figure.IsValid(1.0, nullptr));
}

TEST(RenderCommandTest, IsValidNamesTheBadField) {
  std::string why;
  ASSERT_TRUE(RenderOptions().IsValid(&why)) << why;
  const fs::path dir = fs::path(::testing::TempDir()) / "render_command_test_valid";
  fs::create_directories(dir);
  struct Case {
    std::function<void(RenderOptions*)> change;
    std::string message;  // the start of *why
  };
  const Case cases[] = {
      {[](RenderOptions* o) { o->size = "big"; }, "size: expected WxH in pixels (one panel), e.g. 480x360, got 'big'"},
      {[](RenderOptions* o) { o->size = "0x0"; }, "panel_width x panel_height: panels must be 32..4096 px per side"},
      {[](RenderOptions* o) { o->size = "4000x4000", o->times = DefaultFigureTimes(2.0); },
       "panel_width x panel_height: the figure would have 128000000 pixels"},
      {[](RenderOptions* o) { o->duration = -1.0; }, "duration: must be > 0 s, got -1"},
      {[](RenderOptions* o) { o->duration = NAN; }, "duration: must be > 0 s, got nan"},
      {[](RenderOptions* o) { o->paper_accel_deg_s2 = 0.0; }, "paper_accel_deg_s2: must be > 0 deg/s^2, got 0"},
      {[](RenderOptions* o) { o->times = {0.0, INFINITY}; }, "times: expected finite times [s], got inf"},
      {[](RenderOptions* o) { o->times = std::vector<double>(27, 0.0); }, "times: 27 times given, at most 26"},
      {[](RenderOptions* o) { o->layout = "diagonal"; }, "layout: expected 'grid' or 'strip', got 'diagonal'"},
      {[&](RenderOptions* o) { o->out = dir.string(); }, "out: "},
      {[](RenderOptions* o) { o->base_pose.xyz_rpy[2] = NAN; }, "base_pose"},
  };
  for (const Case& c : cases) {
    RenderOptions options;
    c.change(&options);
    why.clear();
    EXPECT_FALSE(options.IsValid(&why)) << c.message;
    EXPECT_EQ(why.substr(0, c.message.size()), c.message);
  }
  // Times beyond the motion are left to the check against it (the span is
  // not known yet), and so, today, is a negative time (PoseFigureOptions'
  // slack of 1e-9·duration is infinite for the infinite span IsValid uses).
  // No times: the figure size of the default eight panels is checked then too.
  for (double t : {30.0, -0.5}) {
    RenderOptions late;
    late.times = {0.0, t};
    EXPECT_TRUE(late.IsValid(&why)) << why;
    EXPECT_FALSE(late.figure(late.duration).IsValid(late.duration, &why));
    EXPECT_EQ(why, "times: time " + std::string(t > 0 ? "30" : "-0.5") + " s is outside the trajectory [0, 2] s");
  }
  RenderOptions huge;
  huge.size = "4000x4000";
  EXPECT_TRUE(huge.IsValid(&why)) << why;
  EXPECT_FALSE(huge.figure(huge.duration).IsValid(huge.duration, &why));
  EXPECT_EQ(why.substr(0, 67), "panel_width x panel_height: the figure would have 128000000 pixels ");
}

TEST(RenderCommandTest, MakeRenderFigureReadsTheScene) {
  const fs::path dir = fs::path(::testing::TempDir()) / "render_command_test_scene";
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"obstacles": [{"type": "box", "size": [0.6, 0.6, 1.2], "pose": [-0.8, -0.8, 0.6, 0, 0, 0]},
                                            {"type": "box", "size": [0.1, 0.2, 0.3], "pose": [1, 0, 0.15, 0, 0, 0]}]})";
  RenderOptions options;
  options.scene = scene.string();
  const PoseFigureOptions figure = MakeRenderFigure(options, 2.0);
  ASSERT_EQ(figure.scene.obstacles.size(), 2u);
  EXPECT_EQ(figure.times, DefaultFigureTimes(2.0));
  EXPECT_TRUE(MakeRenderFigure(RenderOptions(), 2.0).scene.obstacles.empty());

  options.scene = (dir / "nowhere.json").string();
  try {
    MakeRenderFigure(options, 2.0);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.json"), std::string::npos) << e.what();
  }
}

// The paper's motion: from rest at q = 0, hinges 1 and 2 at qdd, the others
// locked, so q1(t) = q2(t) = ½·qdd·t².
TEST(RenderCommandTest, MakeRenderTrajectoryIsThePapersMotionAtTheOptionsAcceleration) {
  const RobotModel model = MakePaper6r();
  RenderOptions options;
  options.paper_accel_deg_s2 = 60.0;
  options.duration = 3.0;
  const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(model, options);
  ASSERT_EQ(motion->n_dof(), 6);
  EXPECT_DOUBLE_EQ(motion->duration(), 3.0);
  JointState state(6);
  motion->Evaluate(1.0, &state);
  const double qdd = 60.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(state.q[0], 0.5 * qdd, 1e-12);
  EXPECT_NEAR(state.q[1], 0.5 * qdd, 1e-12);
  EXPECT_NEAR(state.qd[0], qdd, 1e-12);
  EXPECT_NEAR(state.qdd[1], qdd, 1e-12);
  for (int i = 2; i < 6; ++i) EXPECT_EQ(state.q[i], 0.0) << i;

  options.trajectory = "nonsense";
  EXPECT_THROW(MakeRenderTrajectory(model, options), std::invalid_argument);
}

class RenderCommandImageTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePaper6r();
};

// A strip of two 160×120 panels: 320×120 pixels, the robot in each, the
// background neutral grey at the corners, and the two instants differ.
TEST_F(RenderCommandImageTest, ImageSizeFromTheOptionsAndTheRobotInEveryPanel) {
  RenderOptions options;
  options.layout = "strip";
  options.size = "160x120";
  options.times = {0.0, 2.0};
  const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(model_, options);
  const PoseFigureOptions figure = MakeRenderFigure(options, motion->duration());
  std::string why;
  ASSERT_TRUE(figure.IsValid(motion->duration(), &why)) << why;
  const Image image = RenderPoseFigureImage(model_, *motion, figure);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 120);
  ASSERT_EQ(image.rgb.size(), 3u * 320 * 120);
  for (int k = 0; k < 2; ++k) {
    const PixelBox box = RobotBox(image, 160 * k, 0, 160, 120);
    EXPECT_GT(box.count, 0.03 * 160 * 120) << "panel " << k;
    EXPECT_GT(box.x0, 160 * k + 1) << "panel " << k;
    EXPECT_LT(box.x1, 160 * k + 160 - 2) << "panel " << k;
  }
  for (const auto& [u, v] : {std::pair{0, 0}, std::pair{319, 0}, std::pair{159, 0}}) {
    const std::uint8_t* p = image.at(u, v);
    EXPECT_FALSE(testing::IsRobotPixel(p)) << u << "," << v;
    EXPECT_LE(std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}), 10) << u << "," << v;
  }
  // Hinges 1 and 2 turn by ½·30°/s²·(2 s)² = 60° between the panels.
  EXPECT_GT(testing::RobotMaskDifference(image, 0, 0, 160, 0, 160, 120), 100);

  // The PNG holds the same pixels.
  const Image decoded = DecodePng(RenderPoseFigurePng(model_, *motion, figure));
  EXPECT_EQ(decoded.width, 320);
  EXPECT_EQ(decoded.height, 120);
  EXPECT_EQ(decoded.rgb, image.rgb);
}

// A box of the cell, beside the robot, appears in its sand colour; without a
// scene almost no pixel has it.
TEST_F(RenderCommandImageTest, SceneBoxIsDrawn) {
  const fs::path dir = fs::path(::testing::TempDir()) / "render_command_test_box";
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"obstacles": [{"type": "box", "size": [0.6, 0.6, 1.2], "pose": [-0.8, -0.8, 0.6, 0, 0, 0]}]})";
  RenderOptions options;
  options.size = "160x120";
  options.times = {0.0};
  const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(model_, options);
  const Image plain = RenderPoseFigureImage(model_, *motion, MakeRenderFigure(options, 2.0));
  options.scene = scene.string();
  const Image cell = RenderPoseFigureImage(model_, *motion, MakeRenderFigure(options, 2.0));
  ASSERT_EQ(plain.width, 160);
  ASSERT_EQ(cell.width, 160);
  ASSERT_EQ(cell.height, 120);
  // Sand (0.74, 0.69, 0.60) lit: red above green above blue, not grey, not a link colour.
  const auto sand = [](const std::uint8_t* p) { return p[0] > p[1] + 4 && p[1] > p[2] + 8 && p[0] - p[2] < 60; };
  long long sand_plain = 0, sand_cell = 0;
  for (int v = 0; v < 120; ++v) {
    for (int u = 0; u < 160; ++u) sand_plain += sand(plain.at(u, v)), sand_cell += sand(cell.at(u, v));
  }
  EXPECT_LT(sand_plain, 0.005 * 160 * 120);
  EXPECT_GT(sand_cell - sand_plain, 0.03 * 160 * 120);
}

// `run`'s figure: its motion (here the paper's over 1 s) at DefaultFigureTimes,
// 480×360 panels in two rows of four, the same bytes as rendering that motion.
TEST_F(RenderCommandImageTest, RunFigureIsTheRunMotionAtTheDefaultInstants) {
  RunOptions run;
  run.duration = 1.0;
  run.sample_times = {0.2, 0.4, 0.6, 0.8};
  const std::string png = RenderRunFigurePng(model_, run);
  const Image figure = DecodePng(png);
  EXPECT_EQ(figure.width, 4 * 480);
  EXPECT_EQ(figure.height, 2 * 360);
  for (int k = 0; k < 8; ++k) {
    EXPECT_GT(RobotBox(figure, (k % 4) * 480, (k / 4) * 360, 480, 360).count, 0.03 * 480 * 360) << "panel " << k;
  }
  RenderOptions options;
  options.duration = 1.0;
  const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(model_, options);
  EXPECT_EQ(png, RenderPoseFigurePng(model_, *motion, MakeRenderFigure(options, 1.0)));
}

}  // namespace
}  // namespace idbench
