#include "idbench/render/plot.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace idbench {
namespace {

constexpr const char* kFont = "DejaVu Sans";
constexpr double kTickFont = 10.0, kLabelFont = 11.0, kTitleFont = 12.0;  // [pt]

// Colours of series, in order (Tableau 10).
const std::array<std::array<double, 3>, 10> kColors{{{0.12, 0.47, 0.71}, {1.00, 0.50, 0.05}, {0.17, 0.63, 0.17},
                                                     {0.84, 0.15, 0.16}, {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29},
                                                     {0.89, 0.47, 0.76}, {0.50, 0.50, 0.50}, {0.74, 0.74, 0.13},
                                                     {0.09, 0.75, 0.81}}};

void SetColor(cairo_t* cr, size_t k) {
  const auto& c = kColors[k % kColors.size()];
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

std::string TickText(double v, bool log) {
  char text[32];
  if (log) {
    std::snprintf(text, sizeof(text), "1e%d", static_cast<int>(std::lround(std::log10(v))));
  } else {
    std::snprintf(text, sizeof(text), "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  }
  return text;
}

double TextWidth(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  return e.x_advance;
}

void ShowText(cairo_t* cr, double x, double y, const std::string& text, double align_x, double angle = 0.0) {
  cairo_save(cr);
  cairo_move_to(cr, x, y);
  cairo_rotate(cr, angle);
  cairo_rel_move_to(cr, -align_x * TextWidth(cr, text), 0.0);
  cairo_show_text(cr, text.c_str());
  cairo_restore(cr);
}

// Data → device mapping of one axes box.
struct Frame {
  double left, top, width, height;  // plot area [pt]
  double x_lo, x_hi, y_lo, y_hi;    // data range (log10 for a log axis)
  bool log_y;
  double X(double x) const { return left + (x - x_lo) / (x_hi - x_lo) * width; }
  double Y(double y) const {
    const double v = log_y ? std::log10(y) : y;
    return top + height - (v - y_lo) / (y_hi - y_lo) * height;
  }
};

// The data range of the axes (y on the log scale: log10 values).
void DataRange(const PlotAxes& axes, double* x_lo, double* x_hi, double* y_lo, double* y_hi) {
  *x_lo = *y_lo = INFINITY;
  *x_hi = *y_hi = -INFINITY;
  bool bars = false;
  for (const PlotSeries& s : axes.series) {
    bars |= s.style == PlotSeries::Style::kBars;
    for (size_t i = 0; i < s.y.size(); ++i) {
      const double e = s.y_error.empty() ? 0.0 : std::abs(s.y_error[i]);
      for (double y : {s.y[i] - e, s.y[i] + e}) {
        if (!std::isfinite(y) || (axes.log_y && y <= 0.0)) continue;
        const double v = axes.log_y ? std::log10(y) : y;
        *y_lo = std::min(*y_lo, v), *y_hi = std::max(*y_hi, v);
      }
      if (std::isfinite(s.x[i])) *x_lo = std::min(*x_lo, s.x[i]), *x_hi = std::max(*x_hi, s.x[i]);
    }
  }
  if (!axes.categories.empty()) {
    *x_lo = -0.5, *x_hi = static_cast<double>(axes.categories.size()) - 0.5;
  } else if (bars) {
    *x_lo -= 0.5, *x_hi += 0.5;
  }
  if (bars && !axes.log_y) *y_lo = std::min(*y_lo, 0.0), *y_hi = std::max(*y_hi, 0.0);
  if (!std::isfinite(*x_lo)) *x_lo = 0.0, *x_hi = 1.0;
  if (!std::isfinite(*y_lo)) *y_lo = 0.0, *y_hi = 1.0;
  if (*x_hi <= *x_lo) *x_lo -= 0.5, *x_hi += 0.5;
  if (*y_hi <= *y_lo) {
    const double pad = std::max(std::abs(*y_lo) * 0.1, axes.log_y ? 0.5 : 1e-9);
    *y_lo -= pad, *y_hi += pad;
  }
  if (axes.log_y) {
    *y_lo = std::floor(*y_lo), *y_hi = std::ceil(*y_hi);
  } else {
    const double pad = 0.05 * (*y_hi - *y_lo);
    if (!(bars && *y_lo == 0.0)) *y_lo -= pad;
    if (!(bars && *y_hi == 0.0)) *y_hi += pad;
  }
}

// Linear ticks for about `target` steps, more when the nice step leaves
// fewer than three (a range of 1.1 in 5 steps rounds up to a step of 0.5).
std::vector<double> AtLeastThreeTicks(double lo, double hi, int target) {
  target = std::max(2, target);
  std::vector<double> ticks = LinearTicks(lo, hi, target);
  for (int more = target + 1; ticks.size() < 3 && more <= 4 * target; ++more) ticks = LinearTicks(lo, hi, more);
  return ticks;
}

// The legend: one line right of the title when it fits beside it, else a
// box of one entry per line in the plot area's top-right corner (never
// beyond the axes' box).
void DrawLegend(cairo_t* cr, const PlotAxes& axes, const Frame& f) {
  constexpr double kSwatch = 12.0, kGap = 4.0, kSpacing = 10.0;  // [pt]
  cairo_set_font_size(cr, kTickFont);
  double line_width = 0.0, widest = 0.0;
  std::vector<size_t> entries;
  for (size_t k = 0; k < axes.series.size(); ++k) {
    if (axes.series[k].label.empty()) continue;
    entries.push_back(k);
    const double w = TextWidth(cr, axes.series[k].label);
    line_width += kSwatch + kGap + w + kSpacing;
    widest = std::max(widest, w);
  }
  if (entries.empty()) return;
  cairo_save(cr);
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, kTitleFont);
  const double title_width = TextWidth(cr, axes.title);
  cairo_restore(cr);
  cairo_set_font_size(cr, kTickFont);
  if (title_width + 12.0 + line_width <= f.width) {
    double legend_x = f.left + f.width;
    for (size_t e = entries.size(); e-- > 0;) {
      const size_t k = entries[e];
      legend_x -= TextWidth(cr, axes.series[k].label);
      cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
      ShowText(cr, legend_x, f.top - 8.0, axes.series[k].label, 0.0);
      legend_x -= kSwatch + kGap;
      SetColor(cr, k);
      cairo_rectangle(cr, legend_x, f.top - 15.0, kSwatch, 8.0);
      cairo_fill(cr);
      legend_x -= kSpacing;
    }
    return;
  }
  const double row = 1.3 * kTickFont, box_w = std::min(f.width, kSwatch + kGap + widest + 10.0);
  const double box_h = row * static_cast<double>(entries.size()) + 6.0;
  const double x = f.left + f.width - box_w, y = f.top;
  cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.85);
  cairo_rectangle(cr, x, y, box_w, box_h);
  cairo_fill(cr);
  for (size_t e = 0; e < entries.size(); ++e) {
    const size_t k = entries[e];
    const double baseline = y + 3.0 + row * static_cast<double>(e + 1) - 3.0;
    SetColor(cr, k);
    cairo_rectangle(cr, x + 4.0, baseline - 8.0, kSwatch, 8.0);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    ShowText(cr, x + 4.0 + kSwatch + kGap, baseline, axes.series[k].label, 0.0);
  }
}

void DrawAxes(cairo_t* cr, const PlotAxes& axes, double x0, double y0, double w, double h) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  // Room for category labels: rotated when they do not fit side by side.
  cairo_set_font_size(cr, kTickFont);
  double longest = 0.0;
  for (const std::string& c : axes.categories) longest = std::max(longest, TextWidth(cr, c));
  const double left_margin = 64.0, right_margin = 14.0, top_margin = 26.0;
  const bool rotate = !axes.categories.empty() &&
                      longest + 4.0 > (w - left_margin - right_margin) / static_cast<double>(axes.categories.size());
  const double bottom_margin = (rotate ? 0.72 * longest + 22.0 : 22.0) + (axes.x_label.empty() ? 0.0 : 16.0);
  Frame f{x0 + left_margin, y0 + top_margin, w - left_margin - right_margin, h - top_margin - bottom_margin,
          0, 0, 0, 0, axes.log_y};
  if (f.width < 10.0 || f.height < 10.0) return;
  DataRange(axes, &f.x_lo, &f.x_hi, &f.y_lo, &f.y_hi);

  // Grid and ticks.
  cairo_set_line_width(cr, 0.6);
  const std::vector<double> y_ticks = axes.log_y ? LogTicks(std::pow(10.0, f.y_lo), std::pow(10.0, f.y_hi))
                                                 : AtLeastThreeTicks(f.y_lo, f.y_hi, static_cast<int>(f.height / 28.0));
  for (double t : y_ticks) {
    const double y = f.Y(t);
    if (y < f.top - 0.5 || y > f.top + f.height + 0.5) continue;
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, f.left, y), cairo_line_to(cr, f.left + f.width, y), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    ShowText(cr, f.left - 5.0, y + 3.5, TickText(t, axes.log_y), 1.0);
  }
  if (!axes.categories.empty()) {
    for (size_t i = 0; i < axes.categories.size(); ++i) {
      const double x = f.X(static_cast<double>(i));
      cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
      if (rotate) {
        ShowText(cr, x + 3.0, f.top + f.height + 10.0, axes.categories[i], 1.0, -std::numbers::pi / 4.0);
      } else {
        ShowText(cr, x, f.top + f.height + 14.0, axes.categories[i], 0.5);
      }
    }
  } else {
    for (double t : AtLeastThreeTicks(f.x_lo, f.x_hi, static_cast<int>(f.width / 70.0))) {
      const double x = f.X(t);
      if (x < f.left - 0.5 || x > f.left + f.width + 0.5) continue;
      cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
      cairo_move_to(cr, x, f.top), cairo_line_to(cr, x, f.top + f.height), cairo_stroke(cr);
      cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
      ShowText(cr, x, f.top + f.height + 14.0, TickText(t, false), 0.5);
    }
  }
  // Zero line of a linear axis with bars.
  if (!axes.log_y && f.y_lo < 0.0 && f.y_hi > 0.0) {
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_move_to(cr, f.left, f.Y(0.0)), cairo_line_to(cr, f.left + f.width, f.Y(0.0)), cairo_stroke(cr);
  }

  // The series, clipped to the plot area.
  cairo_save(cr);
  cairo_rectangle(cr, f.left, f.top, f.width, f.height);
  cairo_clip(cr);
  const auto bar_series = std::count_if(axes.series.begin(), axes.series.end(),
                                        [](const PlotSeries& s) { return s.style == PlotSeries::Style::kBars; });
  const auto marker_series = std::count_if(axes.series.begin(), axes.series.end(),
                                           [](const PlotSeries& s) { return s.style == PlotSeries::Style::kMarkers; });
  int bar_index = 0, marker_index = 0;
  for (size_t k = 0; k < axes.series.size(); ++k) {
    const PlotSeries& s = axes.series[k];
    const auto drawable = [&](size_t i) { return std::isfinite(s.y[i]) && (!axes.log_y || s.y[i] > 0.0); };
    SetColor(cr, k);
    if (s.style == PlotSeries::Style::kLine) {
      cairo_set_line_width(cr, 1.4);
      bool pen_down = false;
      for (size_t i = 0; i < s.y.size(); ++i) {
        if (!drawable(i)) {
          pen_down = false;
          continue;
        }
        if (pen_down) cairo_line_to(cr, f.X(s.x[i]), f.Y(s.y[i]));
        else cairo_move_to(cr, f.X(s.x[i]), f.Y(s.y[i]));
        pen_down = true;
      }
      cairo_stroke(cr);
    }
    // Bars side by side within a category, 80 % of its width; several marker
    // series on categories likewise, so that equal values stay visible.
    const double bar_width = 0.8 / std::max<double>(1.0, static_cast<double>(bar_series));
    const double marker_step = 0.6 / std::max<double>(1.0, static_cast<double>(marker_series));
    double offset = 0.0;
    if (s.style == PlotSeries::Style::kBars) offset = -0.4 + (bar_index + 0.5) * bar_width;
    if (s.style == PlotSeries::Style::kMarkers && marker_series > 1 && !axes.categories.empty()) {
      offset = -0.3 + (marker_index + 0.5) * marker_step;
    }
    for (size_t i = 0; i < s.y.size(); ++i) {
      if (!drawable(i)) continue;
      const double x = f.X(s.x[i] + offset), y = f.Y(s.y[i]);
      if (s.style == PlotSeries::Style::kBars) {
        const double base = axes.log_y ? f.top + f.height : f.Y(0.0);
        const double half = 0.5 * bar_width * f.width / (f.x_hi - f.x_lo);
        cairo_rectangle(cr, x - half, std::min(y, base), 2.0 * half, std::abs(base - y));
        cairo_fill(cr);
      } else if (s.style == PlotSeries::Style::kMarkers) {
        cairo_arc(cr, x, y, 3.2, 0.0, 2.0 * std::numbers::pi);
        cairo_fill(cr);
      }
      if (!s.y_error.empty() && std::isfinite(s.y_error[i]) && s.y_error[i] > 0.0) {
        // Error bar with caps; on a log axis the lower end may leave the axis.
        const double e = std::abs(s.y_error[i]);
        const double lo = axes.log_y && s.y[i] - e <= 0.0 ? f.top + f.height : f.Y(s.y[i] - e);
        const double hi = f.Y(s.y[i] + e);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_set_line_width(cr, 1.0);
        cairo_move_to(cr, x, lo), cairo_line_to(cr, x, hi);
        cairo_move_to(cr, x - 3.0, lo), cairo_line_to(cr, x + 3.0, lo);
        cairo_move_to(cr, x - 3.0, hi), cairo_line_to(cr, x + 3.0, hi);
        cairo_stroke(cr);
        SetColor(cr, k);
      }
    }
    if (s.style == PlotSeries::Style::kBars) ++bar_index;
    if (s.style == PlotSeries::Style::kMarkers) ++marker_index;
  }
  cairo_restore(cr);

  // Frame, labels, legend and title.
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, f.left, f.top, f.width, f.height);
  cairo_stroke(cr);
  cairo_set_font_size(cr, kLabelFont);
  if (!axes.x_label.empty()) ShowText(cr, f.left + 0.5 * f.width, y0 + h - 6.0, axes.x_label, 0.5);
  if (!axes.y_label.empty()) ShowText(cr, x0 + 14.0, f.top + 0.5 * f.height, axes.y_label, 0.5, -std::numbers::pi / 2.0);
  DrawLegend(cr, axes, f);
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, kTitleFont);
  // A title wider than the axes is drawn smaller, not past their box.
  const double title_width = TextWidth(cr, axes.title);
  if (title_width > f.width) cairo_set_font_size(cr, kTitleFont * f.width / title_width);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  ShowText(cr, f.left, f.top - 8.0, axes.title, 0.0);
}

cairo_status_t AppendBytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::vector<double> LinearTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || target < 1) return ticks;
  const double raw = (hi - lo) / target, decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * decade;
    if (step >= raw) break;
  }
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
    ticks.push_back(k == 0.0 ? 0.0 : k * step);
  }
  return ticks;
}

std::vector<double> LogTicks(double lo, double hi) {
  std::vector<double> ticks;
  if (!(lo > 0.0) || !(hi >= lo)) return ticks;
  const int first = static_cast<int>(std::floor(std::log10(lo) + 1e-9)), last = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  const int stride = std::max(1, (last - first + 7) / 8);  // at most about 8 labels
  for (int k = first; k <= last; k += stride) ticks.push_back(std::pow(10.0, k));
  return ticks;
}

void DrawPlotFigure(_cairo* cr, const PlotFigure& figure) {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_rectangle(cr, 0.0, 0.0, figure.width, figure.height);
  cairo_fill(cr);
  const int columns = std::max(1, figure.columns);
  const int rows = std::max(1, (static_cast<int>(figure.axes.size()) + columns - 1) / columns);
  const double w = figure.width / columns, h = figure.height / rows;
  for (size_t k = 0; k < figure.axes.size(); ++k) {
    DrawAxes(cr, figure.axes[k], static_cast<double>(static_cast<int>(k) % columns) * w,
             static_cast<double>(static_cast<int>(k) / columns) * h, w, h);
  }
  cairo_restore(cr);
}

std::string RenderPlot(const PlotFigure& figure, PlotFormat format) {
  if (!(figure.width >= 16 && figure.height >= 16 && figure.width <= 8192 && figure.height <= 8192)) {
    throw std::invalid_argument("plot size: expected 16..8192 per side, got " + std::to_string(figure.width) + "x" +
                                std::to_string(figure.height));
  }
  std::string bytes;
  cairo_surface_t* surface = nullptr;
  switch (format) {
    case PlotFormat::kPng:
      surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(std::lround(figure.width)),
                                           static_cast<int>(std::lround(figure.height)));
      break;
    case PlotFormat::kSvg:
      surface = cairo_svg_surface_create_for_stream(AppendBytes, &bytes, figure.width, figure.height);
      break;
    case PlotFormat::kPdf:
      surface = cairo_pdf_surface_create_for_stream(AppendBytes, &bytes, figure.width, figure.height);
      break;
  }
  cairo_t* cr = cairo_create(surface);
  DrawPlotFigure(cr, figure);
  cairo_destroy(cr);
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (format == PlotFormat::kPng) status = cairo_surface_write_to_png_stream(surface, AppendBytes, &bytes);
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(std::string("cairo: cannot draw the plot: ") + cairo_status_to_string(status));
  }
  return bytes;
}

PlotFormat PlotFormatForPath(const std::string& path) {
  const auto ends_with = [&](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".png")) return PlotFormat::kPng;
  if (ends_with(".svg")) return PlotFormat::kSvg;
  if (ends_with(".pdf")) return PlotFormat::kPdf;
  throw std::invalid_argument(path + ": expected a .png, .svg or .pdf file name");
}

}  // namespace idbench
