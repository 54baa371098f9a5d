#include "idbench/render/pose_figure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/render/osmesa_context.h"
#include "idbench/render/png_codec.h"
#include "render/image_test_util.h"

namespace idbench {
namespace {

using testing::PixelBox;
using testing::RobotBox;
using testing::RobotMaskDifference;

constexpr double kPaperQdd = 30.0 * std::numbers::pi / 180.0;  // [rad/s²]

class PoseFigureTest : public ::testing::Test {
 protected:
  Image Render(const PoseFigureOptions& options) {
    return RenderPoseFigure(renderer_, model_, *motion_, options);
  }
  OsMesaContext context_;
  SceneRenderer renderer_{OsMesaContext::loader(), 4};
  RobotModel model_ = MakePaper6r();
  std::unique_ptr<Trajectory> motion_ = MakePaperMotion(6, kPaperQdd, 2.0);
};

TEST_F(PoseFigureTest, EveryPanelShowsTheWholeRobotAndConsecutivePanelsDiffer) {
  PoseFigureOptions options;  // the paper's eight instants
  options.panel_width = 240, options.panel_height = 180;
  const Image figure = Render(options);
  ASSERT_EQ(figure.width, 4 * 240);
  ASSERT_EQ(figure.height, 2 * 180);
  for (int k = 0; k < 8; ++k) {
    const int x = (k % 4) * 240, y = (k / 4) * 180;
    const PixelBox box = RobotBox(figure, x, y, 240, 180);
    // The robot fills a fair part of the panel and stays clear of its edges.
    EXPECT_GT(box.count, 0.05 * 240 * 180) << "panel " << k;
    EXPECT_GE(box.x0, x + 2) << "panel " << k;
    EXPECT_GE(box.y0, y + 2) << "panel " << k;
    EXPECT_LE(box.x1, x + 240 - 3) << "panel " << k;
    EXPECT_LE(box.y1, y + 180 - 3) << "panel " << k;
    if (k == 0) continue;
    // Hinges 1 and 2 have turned by qdd·(t_k² − t_{k−1}²)/2 ≥ 1.4° since the previous panel.
    const int xp = ((k - 1) % 4) * 240, yp = ((k - 1) / 4) * 180;
    EXPECT_GT(RobotMaskDifference(figure, xp, yp, x, y, 240, 180), 30) << "panels " << k - 1 << ", " << k;
  }
  // Locked at rest: two panels at the same instant are identical.
  options.times = {0.7, 0.7};
  const Image same = Render(options);
  EXPECT_EQ(RobotMaskDifference(same, 0, 0, 240, 0, 240, 180), 0);
}

TEST_F(PoseFigureTest, StripLayoutIsOneRowAndOutputIsDeterministic) {
  PoseFigureOptions options;
  options.times = {0.0, 1.0, 2.0};
  options.layout = "strip";
  options.panel_width = 160, options.panel_height = 120;
  const Image a = Render(options);
  EXPECT_EQ(a.width, 3 * 160);
  EXPECT_EQ(a.height, 120);
  const Image b = Render(options);
  EXPECT_EQ(EncodePng(a), EncodePng(b));
}

// The stored reference (made with `idbench render --times 0,2 --layout strip
// --size 160x120`): the same figure within a small tolerance, so that other
// Mesa versions and fonts pass while a moved camera or robot fails.
TEST_F(PoseFigureTest, MatchesTheStoredReferenceImage) {
  std::ifstream in(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/render/paper6r_0_2s_160x120.png", std::ios::binary);
  ASSERT_TRUE(in) << "reference image missing";
  std::stringstream bytes;
  bytes << in.rdbuf();
  const Image reference = DecodePng(bytes.str());
  PoseFigureOptions options;
  options.times = {0.0, 2.0};
  options.layout = "strip";
  options.panel_width = 160, options.panel_height = 120;
  const Image figure = Render(options);
  ASSERT_EQ(figure.width, reference.width);
  ASSERT_EQ(figure.height, reference.height);
  double sum = 0.0;
  long long far_off = 0;
  for (size_t i = 0; i < figure.rgb.size(); ++i) {
    const int d = std::abs(int(figure.rgb[i]) - int(reference.rgb[i]));
    sum += d;
    far_off += d > 48;
  }
  EXPECT_LT(sum / figure.rgb.size(), 1.5);                        // mean error [levels]
  EXPECT_LT(far_off, static_cast<long long>(0.01 * figure.rgb.size()));  // < 1 % of samples far off
}

TEST(PoseFigureOptionsTest, RejectsBadTimesSizesAndLayouts) {
  std::string why;
  PoseFigureOptions options;
  EXPECT_TRUE(options.IsValid(2.0, &why)) << why;
  options.times = {0.0, 2.5};
  EXPECT_FALSE(options.IsValid(2.0, &why));
  EXPECT_NE(why.find("time 2.5 s is outside the trajectory [0, 2] s"), std::string::npos) << why;
  options.times = {-0.1};
  EXPECT_FALSE(options.IsValid(2.0, &why));
  options = PoseFigureOptions{};
  options.panel_width = 0;
  EXPECT_FALSE(options.IsValid(2.0, &why));
  EXPECT_NE(why.find("--size"), std::string::npos) << why;
  options.panel_width = 4000, options.panel_height = 4000;  // 8 panels: 16000 x 8000 px
  EXPECT_FALSE(options.IsValid(2.0, &why));
  EXPECT_NE(why.find("pixels"), std::string::npos) << why;
  options = PoseFigureOptions{};
  options.layout = "diagonal";
  EXPECT_FALSE(options.IsValid(2.0, &why));
  options = PoseFigureOptions{};
  options.times.assign(27, 0.0);
  EXPECT_FALSE(options.IsValid(2.0, &why));
  EXPECT_EQ(PanelLabel(0, 0.0), "(a) 0 s");
  EXPECT_EQ(PanelLabel(7, 2.0), "(h) 2 s");
  EXPECT_EQ(PanelLabel(1, 0.3), "(b) 0.3 s");
}

}  // namespace
}  // namespace idbench
