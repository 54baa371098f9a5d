// Plots drawn with cairo: one drawing routine for PNG, SVG and PDF (and for a
// page of a report). Axes with ticks, labels with units, legends; linear or
// logarithmic y; lines, markers with error bars, or grouped bars.
#pragma once

#include <string>
#include <vector>

struct _cairo;  // cairo_t

namespace idbench {

struct PlotSeries {
  enum class Style { kLine, kMarkers, kBars };
  std::string label;             // legend entry ("" = none)
  std::vector<double> x, y;      // same size; bars and categories use x = 0, 1, …
  std::vector<double> y_error;   // optional ± half-widths of error bars (size of y, or empty)
  Style style = Style::kLine;
};

struct PlotAxes {
  std::string title;
  std::string x_label, y_label;         // with units: "t [s]"
  bool log_y = false;                   // values <= 0 are not drawn on a log axis
  std::vector<std::string> categories;  // tick labels at x = 0, 1, … instead of numbers
  std::vector<PlotSeries> series;
};

struct PlotFigure {
  std::vector<PlotAxes> axes;  // laid out row by row
  int columns = 1;
  double width = 720.0;        // [pt]; pixels for PNG
  double height = 480.0;       // [pt]
};

enum class PlotFormat { kPng, kSvg, kPdf };

// Draws the figure into the box (0, 0)–(width, height) of the context's user
// space (the caller may translate to place it on a page).
void DrawPlotFigure(_cairo* cr, const PlotFigure& figure);

// The figure as a PNG, SVG or PDF file's bytes. Throws std::runtime_error if
// cairo fails, std::invalid_argument for a size outside [16, 8192].
std::string RenderPlot(const PlotFigure& figure, PlotFormat format);

// The format for a file name's extension (.png, .svg, .pdf); throws
// std::invalid_argument naming the file otherwise.
PlotFormat PlotFormatForPath(const std::string& path);

// Tick positions: "nice" steps (1, 2, 5 × 10^k) covering [lo, hi] for a
// linear axis, about `target` of them; powers of ten for a log axis.
std::vector<double> LinearTicks(double lo, double hi, int target);
std::vector<double> LogTicks(double lo, double hi);

}  // namespace idbench
