// The Design tab's cell and mounting driven headless: a scene file's box
// beside the robot is drawn in the viewport (pixels of the obstacles' sand
// colour appear where there were none), a bad scene file is named with its
// field in the messages, and a design in the cell on a moved base equals
// RunDesign on the same options (the command line's call).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"
#include "workbench/gui/gui_test_util.h"

namespace idbench::gui {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) { return gui::TempDir("design_tab_test", name); }

// Pixels of the viewport in the obstacles' sand (0.74, 0.69, 0.60) lit: red
// above green above blue, not grey, not a link colour (the test of
// render_cli_test's SceneAndBasePoseAreDrawn).
long long SandPixels(HeadlessGui& gui) {
  const WidgetEntry* viewport = gui.widgets().Find("viewport");
  if (!viewport) return -1;
  const Image image = gui.Screenshot();
  long long n = 0;
  for (int v = static_cast<int>(viewport->rect.y0); v < static_cast<int>(viewport->rect.y1); ++v) {
    for (int u = static_cast<int>(viewport->rect.x0); u < static_cast<int>(viewport->rect.x1); ++u) {
      const std::uint8_t* p = image.at(u, v);
      n += p[0] > p[1] + 4 && p[1] > p[2] + 8 && p[0] - p[2] < 60;
    }
  }
  return n;
}

long long ViewportPixels(HeadlessGui& gui) {
  const WidgetRect& r = gui.widgets().Find("viewport")->rect;
  return static_cast<long long>(r.width()) * static_cast<long long>(r.height());
}

TEST(DesignTabTest, SceneIsDrawnAndItsErrorsNamed) {
  const fs::path out = TempDir("draw");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "box", "size": [0.6, 0.6, 1.2],
                              "pose": [-0.8, -0.8, 0.6, 0, 0, 0]}]})";
  const fs::path bad = out / "bad.json";
  std::ofstream(bad) << R"({"obstacles": [{"type": "sphere", "radius": -0.2, "pose": [0, 0, 1, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  RunScript(gui, "frames 2\n");
  const long long plain = SandPixels(gui);
  RunScript(gui, "click tab.design\nset design.scene " + scene.string() + "\nframes 2\n");
  const long long celled = SandPixels(gui);
  std::printf("sand pixels in the viewport: %lld plain, %lld with the box (of %lld)\n", plain, celled,
              ViewportPixels(gui));
  EXPECT_LT(plain, 0.005 * ViewportPixels(gui));
  EXPECT_GT(celled - plain, 0.03 * ViewportPixels(gui));
  EXPECT_EQ(gui.session().last_error(), "");

  // A bad file: its path and the field in the messages, no obstacle drawn.
  RunScript(gui, "set design.scene " + bad.string() + "\nframes 2\n");
  const std::string error = gui.session().last_error();
  EXPECT_NE(error.find("design.scene: "), std::string::npos) << error;
  EXPECT_NE(error.find(bad.string()), std::string::npos) << error;
  EXPECT_NE(error.find("obstacles[0].radius"), std::string::npos) << error;
  EXPECT_LT(SandPixels(gui), 0.005 * ViewportPixels(gui));
  // A base pose that is not six numbers is refused, naming it; the pose kept.
  std::string why;
  EXPECT_FALSE(gui.Set("design.base_pose", "0,0,1", &why));
  EXPECT_NE(why.find("base_pose"), std::string::npos) << why;
  EXPECT_TRUE(gui.session().design.design.base_pose.IsIdentity());
  if (!HasFailure()) fs::remove_all(out);
}

// A design in a cell (a pillar beside the robot) on a base raised and turned:
// the GUI's job equals RunDesign on the same options and limits, keeps the
// clearance to the pillar, and compare gets the same cell and mounting.
TEST(DesignTabTest, DesignInTheCellEqualsRunDesign) {
  const fs::path out = TempDir("design");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "box", "size": [0.4, 0.4, 1.5],
                              "pose": [-1.0, -1.0, 0.75, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nclick limits.fill\nset design.scene " + scene.string() +
                     "\nset design.base_pose 0,0,0.2,0,0,0.5\nset design.harmonics 2\nset design.f0 0.5\n"
                     "set design.samples 40\nset design.max_evaluations 20\nclick design.run\nwait design 300\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  EXPECT_EQ(session.design.scene, scene.string());
  EXPECT_EQ(session.design.design.base_pose.xyz_rpy, (std::array<double, 6>{0, 0, 0.2, 0, 0, 0.5}));
  const DesignResult& shown = session.design_report()->result;
  DesignCommandOptions options = session.design;
  const DesignCommandReport direct = RunDesign(session.model(), options, session.limits, DesignControl{});
  EXPECT_EQ(shown.value, direct.result.value);
  EXPECT_EQ(shown.final.cond, direct.result.final.cond);
  ASSERT_EQ(shown.check.margins.size(), direct.result.check.margins.size());
  // The pillar is among the clearance pairs checked, and kept.
  int pillar = 0;
  for (const ConstraintMargin& m : shown.check.margins) {
    if (m.quantity != "clearance" || m.pair.find("pillar") == std::string::npos) continue;
    ++pillar;
    EXPECT_GE(m.margin, 0.0) << m.pair;
  }
  EXPECT_GT(pillar, 0);
  std::printf("design in the cell: criterion %.17g (RunDesign %.17g), %d pillar margins\n", shown.value,
              direct.result.value, pillar);
  if (!HasFailure()) fs::remove_all(out);
}

// A pillar around the arm leaves it no room (DesignStatus::kNoRoom): the GUI
// says "design failed: " and RunDesign's explanation, word for word, and
// keeps no design.
TEST(DesignTabTest, ACellWithoutRoomIsExplainedAsRunDesignExplainsIt) {
  const fs::path out = TempDir("no_room");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "cylinder", "radius": 0.4, "length": 2,
                              "pose": [0, 0, 1, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nclick limits.fill\nset design.scene " + scene.string() +
                     "\nset design.harmonics 2\nset design.f0 0.5\nset design.samples 40\n"
                     "click design.run\nwait design 300\n");
  EXPECT_FALSE(session.design_report().has_value());
  const DesignCommandReport direct = RunDesign(session.model(), session.design, session.limits, DesignControl{});
  ASSERT_EQ(direct.status(), DesignStatus::kNoRoom) << direct.BriefReport();
  EXPECT_NE(direct.result.infeasibility.explanation.find("pillar"), std::string::npos);
  EXPECT_EQ(session.last_error(), "design failed: " + direct.result.infeasibility.explanation);
  if (!HasFailure()) fs::remove_all(out);
}

}  // namespace
}  // namespace idbench::gui
