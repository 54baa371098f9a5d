#include "pdf_report.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace idbench::internal {
namespace {

constexpr double kPageWidth = 595.0, kPageHeight = 842.0, kMargin = 40.0;  // [pt]
constexpr const char* kSans = "DejaVu Sans";
constexpr const char* kMono = "DejaVu Sans Mono";

// Keeps the text within max_chars, ending in "…" when cut.
std::string Clip(const std::string& text, size_t max_chars) {
  if (text.size() <= max_chars) return text;
  size_t cut = max_chars - 1;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
  return text.substr(0, cut) + "…";
}

class PdfWriter {
 public:
  explicit PdfWriter(std::string* bytes)
      : surface_(cairo_pdf_surface_create_for_stream(&Append, bytes, kPageWidth, kPageHeight)),
        cr_(cairo_create(surface_)) {}
  ~PdfWriter() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
  }
  // Ends the document. Throws std::runtime_error if cairo failed.
  void Finish() {
    cairo_surface_finish(surface_);
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
      throw std::runtime_error(std::string("cairo: cannot write the PDF report: ") +
                               cairo_status_to_string(cairo_surface_status(surface_)));
    }
  }

  // Starts a new page unless `height` more points fit on this one.
  void Reserve(double height) {
    if (y_ + height <= kPageHeight - kMargin) return;
    cairo_show_page(cr_);
    y_ = kMargin;
  }

  void Text(const std::string& text, double size, bool bold = false, const char* font = kSans) {
    cairo_select_font_face(cr_, font, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
    Reserve(1.4 * size);
    cairo_set_source_rgb(cr_, 0, 0, 0);
    cairo_move_to(cr_, kMargin, y_ + size);
    cairo_show_text(cr_, text.c_str());
    y_ += 1.4 * size;
  }

  // Monospaced text broken into lines that fit the page width.
  void Wrapped(const std::string& text, double size) {
    const size_t per_line = static_cast<size_t>((kPageWidth - 2 * kMargin) / (0.602 * size));
    for (size_t i = 0; i < text.size(); i += per_line) Text(text.substr(i, per_line), size, false, kMono);
  }

  void Space(double height) { y_ += height; }

  void Png(const std::string& png, double width) {
    struct Reader {
      const std::string* bytes;
      size_t at = 0;
    } reader{&png};
    cairo_surface_t* image = cairo_image_surface_create_from_png_stream(
        [](void* closure, unsigned char* data, unsigned int length) {
          Reader* r = static_cast<Reader*>(closure);
          if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
          std::copy_n(r->bytes->data() + r->at, length, data);
          r->at += length;
          return CAIRO_STATUS_SUCCESS;
        },
        &reader);
    const double scale = width / cairo_image_surface_get_width(image);
    const double height = scale * cairo_image_surface_get_height(image);
    Reserve(height);
    cairo_save(cr_);
    cairo_translate(cr_, kMargin, y_);
    cairo_scale(cr_, scale, scale);
    cairo_set_source_surface(cr_, image, 0, 0);
    cairo_paint(cr_);
    cairo_restore(cr_);
    cairo_surface_destroy(image);
    y_ += height + 6.0;
  }

  void Plot(const PlotFigure& figure) {
    const double scale = (kPageWidth - 2 * kMargin) / figure.width;
    Reserve(scale * figure.height);
    cairo_save(cr_);
    cairo_translate(cr_, kMargin, y_);
    cairo_scale(cr_, scale, scale);
    DrawPlotFigure(cr_, figure);
    cairo_restore(cr_);
    y_ += scale * figure.height + 6.0;
  }

  // A table with columns as wide as their widest cell, shrunk to the page.
  void Table(const ReportTable& table) {
    Text(table.caption, 10.0, true);
    double size = 7.5;
    cairo_set_font_size(cr_, size);
    std::vector<double> widths(table.header.size(), 0.0);
    // Measured in the weight each row is drawn in (the header bold).
    const auto measure = [&](const std::vector<std::string>& row, bool bold) {
      cairo_select_font_face(cr_, kSans, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
      for (size_t c = 0; c < row.size() && c < widths.size(); ++c) {
        cairo_text_extents_t e;
        cairo_text_extents(cr_, Clip(row[c], 60).c_str(), &e);
        widths[c] = std::max(widths[c], e.x_advance + 8.0);
      }
    };
    measure(table.header, true);
    for (const auto& row : table.rows) measure(row, false);
    double total = 0.0;
    for (double w : widths) total += w;
    const double shrink = std::min(1.0, (kPageWidth - 2 * kMargin) / total);
    size *= shrink;
    const auto draw_row = [&](const std::vector<std::string>& row, bool bold) {
      Reserve(1.35 * size);
      cairo_select_font_face(cr_, kSans, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
      cairo_set_font_size(cr_, size);
      double x = kMargin;
      for (size_t c = 0; c < row.size() && c < widths.size(); ++c) {
        cairo_move_to(cr_, x, y_ + size);
        cairo_show_text(cr_, Clip(row[c], 60).c_str());
        x += widths[c] * shrink;
      }
      y_ += 1.35 * size;
    };
    draw_row(table.header, true);
    for (const auto& row : table.rows) draw_row(row, false);
    Space(8.0);
  }

 private:
  static cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
  }
  cairo_surface_t* surface_;
  cairo_t* cr_;
  double y_ = kMargin;
};

}  // namespace

std::string FormatPdf(const ReportContent& content) {
  std::string bytes;
  PdfWriter pdf(&bytes);
  pdf.Text(content.title, 16.0, true);
  pdf.Space(4.0);
  pdf.Text("Reproduce with:", 9.0, true);
  pdf.Wrapped(content.command, 8.0);
  pdf.Space(6.0);
  for (const auto& [key, value] : content.experiment) pdf.Text(key + ": " + value, 9.0);
  pdf.Space(6.0);
  if (!content.pose_figure_png.empty()) {
    pdf.Png(content.pose_figure_png, kPageWidth - 2 * kMargin);
    pdf.Text(content.pose_caption, 8.5);
    pdf.Space(8.0);
  }
  for (const ReportTable& table : content.tables) pdf.Table(table);
  for (const ReportPlot& plot : content.plots) {
    pdf.Plot(plot.figure);
    pdf.Text(plot.caption, 8.5);
    pdf.Space(8.0);
  }
  pdf.Finish();
  return bytes;
}

}  // namespace idbench::internal
