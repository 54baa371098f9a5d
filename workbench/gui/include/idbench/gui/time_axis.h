// The time axis of a plot: pixels [x0, x1] show times [t0, t1] linearly. A
// drag across the plot selects a time window (IdentifyOptions::time_window).
#pragma once

#include <vector>

namespace idbench::gui {

struct TimeAxis {
  double x0 = 0.0, x1 = 1.0;  // [px] left and right edges of the plot (x1 > x0)
  double t0 = 0.0, t1 = 1.0;  // [s] times at the edges (t1 > t0)

  // t0 + (x − x0) / (x1 − x0) · (t1 − t0), with x clamped to [x0, x1].
  double TimeAt(double x) const;
  // The inverse, unclamped.
  double PixelAt(double t) const;
};

// The window {T0, T1}, T0 < T1, a drag from pixel xa to xb selects (either
// direction, clamped to the plot); empty (the whole log) when the drag spans
// less than min_pixels (a click).
std::vector<double> DraggedTimeWindow(const TimeAxis& axis, double xa, double xb, double min_pixels = 3.0);

}  // namespace idbench::gui
