#include "idbench/render/pose_figure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "idbench/engine/kinematics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/render/osmesa_context.h"
#include "idbench/render/png_codec.h"
#include "idbench/render/robot_scene.h"
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

// A big box beside the robot, one camera for both renders: the pixels where
// the box projects change (it is drawn), the robot's own pixels elsewhere do
// not (the box takes nothing from it); and the figure with the cell keeps the
// box in view.
TEST_F(PoseFigureTest, TheCellsObstaclesAreDrawnBesideTheRobot) {
  const int w = 320, h = 240;
  RobotData data(model_);
  const JointState state = motion_->At(1.0);
  ComputeKinematics(model_, state.q, state.qd, state.qdd, &data);
  const Scene robot = BuildRobotScene(model_, data);
  Cell cell;
  Obstacle box;
  box.name = "cabinet";
  box.shape.kind = Shape::Kind::kBox;
  box.shape.size = Eigen::Vector3d(0.6, 0.6, 1.2);
  // Beside the robot in the image: along the camera's right, (cos, sin)(azimuth + 90°), past the robot's reach.
  std::vector<Eigen::Vector3d> points = robot.BoundingPoints();
  Eigen::Vector3d lo = points.front(), hi = lo;
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double azimuth = CameraView{}.azimuth + std::numbers::pi / 2.0;
  const Eigen::Vector2d right(std::cos(azimuth), std::sin(azimuth));
  const Eigen::Vector2d centre = 0.5 * (lo + hi).head<2>() + (0.5 * (hi - lo).head<2>().norm() + 0.6) * right;
  box.X_WO.translation() = Eigen::Vector3d(centre.x(), centre.y(), 0.6);
  cell.obstacles = {box};
  Scene with_box = robot;
  AddCellObstacles(cell, &with_box);
  const std::vector<Eigen::Vector3d> all = with_box.BoundingPoints();
  const Camera camera = FitCamera(all, double(w) / h);
  const Floor floor = FitFloor(all);
  const Image a = renderer_.Render(robot, floor, camera, w, h);
  const Image b = renderer_.Render(with_box, floor, camera, w, h);
  // The box's projected rectangle (its 8 corners through the pinhole).
  const Eigen::Matrix4d P = camera.Projection(double(w) / h) * camera.View();
  int u0 = w, v0 = h, u1 = 0, v1 = 0;
  Scene only_box;
  AddCellObstacles(cell, &only_box);
  for (const Eigen::Vector3d& p_W : only_box.BoundingPoints()) {
    const Eigen::Vector4d c = P * p_W.homogeneous();
    const double u = (0.5 + 0.5 * c.x() / c.w()) * w, v = (0.5 - 0.5 * c.y() / c.w()) * h;
    u0 = std::min(u0, int(std::floor(u))), u1 = std::max(u1, int(std::ceil(u)));
    v0 = std::min(v0, int(std::floor(v))), v1 = std::max(v1, int(std::ceil(v)));
  }
  u0 = std::max(u0, 0), v0 = std::max(v0, 0), u1 = std::min(u1, w - 1), v1 = std::min(v1, h - 1);
  ASSERT_GT(u1 - u0, 10);
  ASSERT_GT(v1 - v0, 10);
  const auto differs = [&](int u, int v) {
    int d = 0;
    for (int k = 0; k < 3; ++k) d += std::abs(int(a.at(u, v)[k]) - int(b.at(u, v)[k]));
    return d > 12;
  };
  // The box's silhouette is a hexagon inside its rectangle: most of the rectangle's centre changes.
  long long inside = 0, changed = 0;
  for (int v = v0 + (v1 - v0) / 4; v <= v1 - (v1 - v0) / 4; ++v) {
    for (int u = u0 + (u1 - u0) / 4; u <= u1 - (u1 - u0) / 4; ++u) ++inside, changed += differs(u, v);
  }
  EXPECT_GT(changed, 0.9 * inside) << changed << " of " << inside;
  // The robot's pixels outside the rectangle (2 px for antialiasing) are
  // untouched: those inside its silhouette (an edge pixel blends in the floor
  // behind it, which the box's shadow may darken).
  const auto robot_inside = [&](int u, int v) {
    return u > 0 && v > 0 && u + 1 < w && v + 1 < h && testing::IsRobotPixel(a.at(u, v)) &&
           testing::IsRobotPixel(a.at(u - 1, v)) && testing::IsRobotPixel(a.at(u + 1, v)) &&
           testing::IsRobotPixel(a.at(u, v - 1)) && testing::IsRobotPixel(a.at(u, v + 1));
  };
  long long robot_pixels = 0, robot_changed = 0;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      if (u >= u0 - 2 && u <= u1 + 2 && v >= v0 - 2 && v <= v1 + 2) continue;
      if (!robot_inside(u, v)) continue;
      ++robot_pixels, robot_changed += differs(u, v);
    }
  }
  EXPECT_GT(robot_pixels, 0.02 * w * h);
  EXPECT_EQ(robot_changed, 0);
  // The figure with the cell shows the box as well as the robot.
  PoseFigureOptions options;
  options.times = {1.0};
  options.panel_width = w, options.panel_height = h;
  const Image plain = Render(options);
  options.scene = cell;
  const Image celled = Render(options);
  long long figure_changed = 0;
  for (size_t i = 0; i < plain.rgb.size(); i += 3) figure_changed += std::abs(int(plain.rgb[i]) - int(celled.rgb[i])) > 12;
  EXPECT_GT(figure_changed, 0.05 * w * h);
  EXPECT_GT(RobotBox(celled, 0, 0, w, h).count, 0.02 * w * h);
}

// Mounted on a ceiling (base 2.5 m up, turned over about x): the robot hangs
// from its base. Upright, the first link (the only blue one) is at the bottom
// of the robot in the image; on the ceiling, at the top.
TEST_F(PoseFigureTest, ACeilingMountedRobotHangsUpsideDown) {
  const auto base_row_below_centroid = [&](const BasePose& pose) {
    PoseFigureOptions options;
    options.times = {0.0};
    options.panel_width = 320, options.panel_height = 240;
    options.base_pose = pose;
    return testing::FirstLinkBelowCentroid(Render(options));
  };
  const double upright = base_row_below_centroid(BasePose{});
  const double ceiling = base_row_below_centroid(BasePose{{0, 0, 2.5, std::numbers::pi, 0, 0}});
  EXPECT_GT(upright, 10.0);
  EXPECT_LT(ceiling, -10.0);
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
  EXPECT_EQ(why.rfind("panel_width x panel_height: panels must be 32..4096 px per side", 0), 0u) << why;
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
