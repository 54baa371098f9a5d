#include "idbench/workbench/commands/render_command.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/render/osmesa_context.h"
#include "idbench/render/png_codec.h"
#include "idbench/render/scene_renderer.h"
#include "number_format.h"
#include "idbench/workbench/formats/scene_file.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench {

bool ParseImageSize(const std::string& text, int* width, int* height) {
  const size_t x = text.find('x');
  if (x == std::string::npos) return false;
  const auto parse = [](const char* first, const char* last, int* value) {
    const auto [end, ec] = std::from_chars(first, last, *value);
    return ec == std::errc() && end == last && first != last;
  };
  return parse(text.data(), text.data() + x, width) && parse(text.data() + x + 1, text.data() + text.size(), height);
}

PoseFigureOptions RenderOptions::figure(double duration) const {
  PoseFigureOptions figure;
  figure.times = times.empty() ? DefaultFigureTimes(duration) : times;
  figure.layout = layout;
  figure.base_pose = base_pose;
  if (!ParseImageSize(size, &figure.panel_width, &figure.panel_height)) figure.panel_width = figure.panel_height = 0;
  return figure;
}

bool RenderOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  int width = 0, height = 0;
  if (!ParseImageSize(size, &width, &height)) {
    return fail("size: expected WxH in pixels (one panel), e.g. 480x360, got '" + size + "'");
  }
  if (!std::isfinite(duration) || duration <= 0.0) return fail("duration: must be > 0 s, got " + Shortest(duration));
  if (!std::isfinite(paper_accel_deg_s2) || paper_accel_deg_s2 <= 0.0) {
    return fail("paper_accel_deg_s2: must be > 0 deg/s^2, got " + Shortest(paper_accel_deg_s2));
  }
  if (std::string out_why; !IsUsableOutputFile(out, "out", &out_why)) return fail(out_why);
  // The times alone here (the trajectory's span is not known yet: no "[0, inf]"),
  // then everything but the times against the trajectory, checked once it is known.
  for (double t : times) {
    if (!std::isfinite(t)) return fail("times: expected finite times [s], got " + Shortest(t));
  }
  if (!base_pose.IsValid(why)) return false;
  PoseFigureOptions figure = this->figure(0.0);
  if (times.empty()) figure.times = {0.0};  // the default times fit any motion
  return figure.IsValid(INFINITY, why);
}

std::vector<double> DefaultFigureTimes(double duration) {
  std::vector<double> times;
  for (int k = 0; k < 8; ++k) {
    // Rounded to 3 significant digits, so that labels read 0.9 s, not 0.8999999999999999 s.
    const double t = 0.15 * k * duration;
    const double unit = t > 0.0 ? std::pow(10.0, std::floor(std::log10(t)) - 2.0) : 1.0;
    times.push_back(std::min(std::round(t / unit) * unit, duration));
  }
  return times;
}

PoseFigureOptions MakeRenderFigure(const RenderOptions& options, double duration) {
  PoseFigureOptions figure = options.figure(duration);
  if (!options.scene.empty()) figure.scene = ReadSceneFile(options.scene);
  return figure;
}

std::unique_ptr<Trajectory> MakeRenderTrajectory(const RobotModel& model, const RenderOptions& options) {
  return LoadTrajectoryArg(options.trajectory, model,
                           {.duration = options.duration, .paper_qdd = options.paper_accel_deg_s2 * std::numbers::pi / 180.0});
}

Image RenderPoseFigureImage(const RobotModel& model, const Trajectory& trajectory, const PoseFigureOptions& options) {
  OsMesaContext context;
  SceneRenderer renderer(OsMesaContext::loader(), 4);
  return RenderPoseFigure(renderer, model, trajectory, options);
}

std::string RenderPoseFigurePng(const RobotModel& model, const Trajectory& trajectory,
                                const PoseFigureOptions& options) {
  return EncodePng(RenderPoseFigureImage(model, trajectory, options));
}

std::string RenderRunFigurePng(const RobotModel& model, const RunOptions& options) {
  const std::unique_ptr<Trajectory> motion = MakeRunMotion(model, options);
  PoseFigureOptions figure;
  figure.times = DefaultFigureTimes(options.duration);
  return RenderPoseFigurePng(model, *motion, figure);
}

}  // namespace idbench
