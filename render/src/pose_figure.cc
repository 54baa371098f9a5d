#include "idbench/render/pose_figure.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "idbench/engine/kinematics.h"
#include "idbench/render/robot_scene.h"

namespace idbench {
namespace {

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

// Draws each panel's label in its top-left corner, black on the background,
// with cairo (an RGB24 surface over a copy of the pixels).
void DrawLabels(const std::vector<std::string>& labels, const PoseFigureOptions& options, Image* figure) {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, figure->width, figure->height);
  const int stride = cairo_image_surface_get_stride(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  // Cairo's RGB24 is a native-endian 32-bit 0xXXRRGGBB per pixel.
  const auto pixel = [&](int x, int y) { return reinterpret_cast<uint32_t*>(data + static_cast<size_t>(y) * stride) + x; };
  for (int y = 0; y < figure->height; ++y) {
    for (int x = 0; x < figure->width; ++x) {
      const std::uint8_t* p = figure->at(x, y);
      *pixel(x, y) = (uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | uint32_t(p[2]);
    }
  }
  cairo_surface_mark_dirty(surface);
  cairo_t* cr = cairo_create(surface);
  const double font_px = std::max(12.0, std::round(options.panel_height / 16.0));
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font_px);
  for (size_t k = 0; k < labels.size(); ++k) {
    const int column = static_cast<int>(k) % options.columns(), row = static_cast<int>(k) / options.columns();
    const double x0 = column * options.panel_width, y0 = row * options.panel_height;
    // A thin frame between panels, then the label.
    cairo_set_source_rgb(cr, 0.78, 0.78, 0.80);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, options.panel_width - 1.0, options.panel_height - 1.0);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_move_to(cr, x0 + 0.6 * font_px, y0 + 1.5 * font_px);
    cairo_show_text(cr, labels[k].c_str());
  }
  cairo_destroy(cr);
  cairo_surface_flush(surface);
  for (int y = 0; y < figure->height; ++y) {
    for (int x = 0; x < figure->width; ++x) {
      const uint32_t v = *pixel(x, y);
      std::uint8_t* p = figure->at(x, y);
      p[0] = std::uint8_t(v >> 16), p[1] = std::uint8_t(v >> 8), p[2] = std::uint8_t(v);
    }
  }
  cairo_surface_destroy(surface);
}

}  // namespace

int PoseFigureOptions::columns() const {
  const int n = std::max(1, static_cast<int>(times.size()));
  return layout == "strip" ? n : std::min(n, kGridColumns);
}

int PoseFigureOptions::rows() const {
  const int n = std::max(1, static_cast<int>(times.size()));
  return (n + columns() - 1) / columns();
}

bool PoseFigureOptions::IsValid(double duration, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (layout != "grid" && layout != "strip") return fail("layout: expected 'grid' or 'strip', got '" + layout + "'");
  if (times.empty()) return fail("times: no time given");
  if (static_cast<int>(times.size()) > kMaxPanels) {
    return fail("times: " + std::to_string(times.size()) + " times given, at most " + std::to_string(kMaxPanels));
  }
  const double slack = 1e-9 * std::max(1.0, duration);
  for (double t : times) {
    if (!std::isfinite(t) || t < -slack || t > duration + slack) {
      return fail("times: time " + Number(t) + " s is outside the trajectory [0, " + Number(duration) + "] s");
    }
  }
  for (int side : {panel_width, panel_height}) {
    if (side < kMinPanelSize || side > kMaxPanelSize) {
      return fail("panel_width x panel_height: panels must be " + std::to_string(kMinPanelSize) + ".." + std::to_string(kMaxPanelSize) +
                  " px per side, got " + std::to_string(panel_width) + "x" + std::to_string(panel_height));
    }
  }
  const long long pixels = 1LL * columns() * panel_width * rows() * panel_height;
  if (pixels > kMaxPixels) {
    return fail("panel_width x panel_height: the figure would have " + std::to_string(pixels) + " pixels (" +
                std::to_string(columns() * panel_width) + "x" + std::to_string(rows() * panel_height) +
                "), at most " + std::to_string(kMaxPixels));
  }
  return true;
}

std::string PanelLabel(int k, double t) {
  return "(" + std::string(1, static_cast<char>('a' + k)) + ") " + Number(t) + " s";
}

Image RenderPoseFigure(SceneRenderer& renderer, const RobotModel& model, const Trajectory& trajectory,
                       const PoseFigureOptions& options) {
  // The robot at every time, clamped onto the trajectory's domain, in the cell.
  std::vector<Scene> scenes;
  std::vector<Eigen::Vector3d> points;
  RobotData data(model);
  const Eigen::Isometry3d X_WR = options.base_pose.X_WR();
  for (double t : options.times) {
    const JointState state = trajectory.At(std::clamp(t, 0.0, trajectory.duration()));
    ComputeKinematics(model, state.q, state.qd, state.qdd, &data);
    scenes.push_back(BuildRobotScene(model, data, X_WR));
    const std::vector<Eigen::Vector3d> p = scenes.back().BoundingPoints();
    points.insert(points.end(), p.begin(), p.end());
  }
  Scene cell;
  AddCellObstacles(options.scene, &cell);
  if (!cell.primitives.empty() && !points.empty()) {
    // The obstacles near the robot in view.
    const std::vector<Eigen::Vector3d> near = CellPointsNearRobot(cell, points);
    points.insert(points.end(), near.begin(), near.end());
    for (Scene& scene : scenes) scene.primitives.insert(scene.primitives.end(), cell.primitives.begin(), cell.primitives.end());
  }
  // One camera and one floor for all panels.
  const Camera camera = FitCamera(points, double(options.panel_width) / options.panel_height, options.view);
  const Floor floor = FitFloor(points);
  Image figure(options.columns() * options.panel_width, options.rows() * options.panel_height, 255);
  std::vector<std::string> labels;
  for (size_t k = 0; k < scenes.size(); ++k) {
    const Image panel = renderer.Render(scenes[k], floor, camera, options.panel_width, options.panel_height);
    const int column = static_cast<int>(k) % options.columns(), row = static_cast<int>(k) / options.columns();
    figure.Paste(panel, column * options.panel_width, row * options.panel_height);
    labels.push_back(PanelLabel(static_cast<int>(k), options.times[k]));
  }
  DrawLabels(labels, options, &figure);
  return figure;
}

}  // namespace idbench
