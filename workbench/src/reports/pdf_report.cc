#include "pdf_report.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace idbench::internal {
namespace {

constexpr double kPageWidth = 595.0, kPageHeight = 842.0, kMargin = 40.0;  // [pt]
constexpr double kTextWidth = kPageWidth - 2 * kMargin;                     // [pt]
constexpr const char* kSans = "DejaVu Sans";
constexpr const char* kMono = "DejaVu Sans Mono";

// The byte length of the UTF-8 character starting at text[i].
size_t CharLength(const std::string& text, size_t i) {
  size_t n = 1;
  while (i + n < text.size() && (static_cast<unsigned char>(text[i + n]) & 0xC0) == 0x80) ++n;
  return n;
}

// Breaks `text` into lines no wider than `width` as `measure` measures them:
// at spaces, and inside a word (between UTF-8 characters) only when the word
// alone is wider than a line. Nothing is cut: the lines hold every character.
std::vector<std::string> BreakLines(const std::string& text, double width,
                                    const std::function<double(const std::string&)>& measure) {
  std::vector<std::string> lines;
  std::string line;
  size_t i = 0;
  while (i < text.size()) {
    // The next word with the spaces before it.
    size_t end = i;
    while (end < text.size() && text[end] == ' ') ++end;
    while (end < text.size() && text[end] != ' ') ++end;
    const std::string piece = text.substr(i, end - i);
    if (measure(line + piece) <= width) {
      line += piece;
      i = end;
      continue;
    }
    if (!line.empty()) {  // the word starts the next line, without its spaces
      lines.push_back(line);
      line.clear();
      while (i < text.size() && text[i] == ' ') ++i;
      continue;
    }
    // A word wider than a line: as many characters as fit (at least one).
    size_t cut = i + CharLength(text, i);
    while (cut < end && measure(text.substr(i, cut + CharLength(text, cut) - i)) <= width) cut += CharLength(text, cut);
    lines.push_back(text.substr(i, cut - i));
    i = cut;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
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

  // Text broken into lines that fit the page width (BreakLines).
  void Text(const std::string& text, double size, bool bold = false, const char* font = kSans) {
    SetFont(font, size, bold);
    cairo_set_source_rgb(cr_, 0, 0, 0);
    for (const std::string& line : BreakLines(text, kTextWidth, [&](const std::string& t) { return Width(t); })) {
      Reserve(1.4 * size);
      cairo_move_to(cr_, kMargin, y_ + size);
      cairo_show_text(cr_, line.c_str());
      y_ += 1.4 * size;
    }
  }

  // Monospaced text broken into lines that fit the page width.
  void Wrapped(const std::string& text, double size) { Text(text, size, false, kMono); }

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

  // A table with columns as wide as their widest cell, up to kMaxColumnShare
  // of the text width (longer cells wrap within it), shrunk to the page.
  void Table(const ReportTable& table) {
    Text(table.caption, 10.0, true);
    constexpr double kPadding = 8.0, kMaxColumnShare = 0.45;
    double size = 7.5;
    std::vector<double> widths(table.header.size(), 0.0);
    // Measured in the weight each row is drawn in (the header bold).
    const auto measure = [&](const std::vector<std::string>& row, bool bold) {
      SetFont(kSans, size, bold);
      for (size_t c = 0; c < row.size() && c < widths.size(); ++c) {
        widths[c] = std::max(widths[c], std::min(Width(row[c]) + kPadding, kMaxColumnShare * kTextWidth));
      }
    };
    measure(table.header, true);
    for (const auto& row : table.rows) measure(row, false);
    double total = 0.0;
    for (double w : widths) total += w;
    const double shrink = std::min(1.0, kTextWidth / total);
    size *= shrink;
    const auto draw_row = [&](const std::vector<std::string>& row, bool bold) {
      SetFont(kSans, size, bold);
      std::vector<std::vector<std::string>> cells;
      size_t n_lines = 1;
      for (size_t c = 0; c < row.size() && c < widths.size(); ++c) {
        // 1 pt of the padding spare: text does not scale exactly with the font size.
        cells.push_back(BreakLines(row[c], (widths[c] - kPadding) * shrink + 1.0,
                                   [&](const std::string& t) { return Width(t); }));
        n_lines = std::max(n_lines, cells.back().size());
      }
      Reserve(1.35 * size * static_cast<double>(n_lines));
      double x = kMargin;
      for (size_t c = 0; c < cells.size(); ++c) {
        for (size_t l = 0; l < cells[c].size(); ++l) {
          cairo_move_to(cr_, x, y_ + size + 1.35 * size * static_cast<double>(l));
          cairo_show_text(cr_, cells[c][l].c_str());
        }
        x += widths[c] * shrink;
      }
      y_ += 1.35 * size * static_cast<double>(n_lines);
    };
    draw_row(table.header, true);
    for (const auto& row : table.rows) draw_row(row, false);
    Space(8.0);
  }

 private:
  void SetFont(const char* font, double size, bool bold) {
    cairo_select_font_face(cr_, font, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }
  // The advance of `text` in the current font [pt].
  double Width(const std::string& text) {
    cairo_text_extents_t e;
    cairo_text_extents(cr_, text.c_str(), &e);
    return e.x_advance;
  }
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
