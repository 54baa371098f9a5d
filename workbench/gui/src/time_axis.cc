#include "idbench/gui/time_axis.h"

#include <algorithm>
#include <cmath>

namespace idbench::gui {

double TimeAxis::TimeAt(double x) const {
  const double s = (std::clamp(x, x0, x1) - x0) / (x1 - x0);
  return t0 + s * (t1 - t0);
}

double TimeAxis::PixelAt(double t) const { return x0 + (t - t0) / (t1 - t0) * (x1 - x0); }

std::vector<double> DraggedTimeWindow(const TimeAxis& axis, double xa, double xb, double min_pixels) {
  const double a = std::clamp(std::min(xa, xb), axis.x0, axis.x1), b = std::clamp(std::max(xa, xb), axis.x0, axis.x1);
  if (b - a < min_pixels) return {};
  return {axis.TimeAt(a), axis.TimeAt(b)};
}

}  // namespace idbench::gui
