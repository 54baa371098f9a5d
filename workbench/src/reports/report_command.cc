#include "idbench/engine/printable_text.h"
#include "idbench/workbench/reports/report_command.h"

#include "number_format.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/urdf.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/workbench/reports/plots.h"
#include "idbench/workbench/commands/render_command.h"

namespace idbench {
namespace {


// The built-in motion a run is compared with: the other one, or the paper's
// for a trajectory file.
std::string OtherMotion(const std::string& motion) { return motion == "paper" ? "general" : "paper"; }

// A joint log played back as a trajectory (the nearest sample at or before t),
// to draw the poses of a recorded experiment.
class JointLogPlayback final : public Trajectory {
 public:
  explicit JointLogPlayback(const JointLog& log) : log_(log) {}
  int n_dof() const override { return log_.n_dof(); }
  double duration() const override { return log_.t[log_.n_samples() - 1] - log_.t[0]; }
  void Evaluate(double t, JointState* state) const override {
    const double* begin = log_.t.data();
    const auto it = std::upper_bound(begin, begin + log_.n_samples(), log_.t[0] + t + 1e-12);
    const Eigen::Index i = std::max<Eigen::Index>(0, (it - begin) - 1);
    state->q = log_.q.row(i).transpose();
    state->qd.setZero(), state->qdd.setZero();
  }

 private:
  const JointLog& log_;
};

// --- The PDF: A4 pages drawn with cairo ------------------------------------

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

// --- The HTML page -----------------------------------------------------------

std::string FormatHtml(const ReportContent& content) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + EscapeHtml(content.title) +
      "</title>\n<style>\n"
      "body{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;"
      "color:#222}\n"
      "pre{background:#f4f4f6;padding:.6em;white-space:pre-wrap;word-break:break-all}\n"
      "table{border-collapse:collapse;font-size:.85em;margin:.5em 0 1.5em}\n"
      "th,td{border:1px solid #ccc;padding:.2em .5em;text-align:right}\n"
      "th{background:#eee}td:first-child,td:nth-child(2){text-align:left}\n"
      "img{max-width:100%}figure{margin:1em 0}figcaption{font-size:.9em;color:#444}\n"
      "</style>\n</head>\n<body>\n";
  html += "<h1>" + EscapeHtml(content.title) + "</h1>\n";
  html += "<p>Reproduce with:</p>\n<pre>" + EscapeHtml(content.command) + "</pre>\n";
  html += "<p>The same report as <a href=\"report.pdf\">PDF</a>.</p>\n<h2>Experiment</h2>\n<table>\n";
  for (const auto& [key, value] : content.experiment) {
    html += "<tr><td>" + EscapeHtml(key) + "</td><td>" + EscapeHtml(value) + "</td></tr>\n";
  }
  html += "</table>\n";
  if (!content.pose_figure_png.empty()) {
    html += "<figure><img src=\"figure.png\" alt=\"poses\"><figcaption>" + EscapeHtml(content.pose_caption) +
            "</figcaption></figure>\n";
  }
  for (const ReportTable& table : content.tables) {
    html += "<h2>" + EscapeHtml(table.caption) + "</h2>\n<table>\n<tr>";
    for (const std::string& h : table.header) html += "<th>" + EscapeHtml(h) + "</th>";
    html += "</tr>\n";
    for (const auto& row : table.rows) {
      html += "<tr>";
      for (const std::string& cell : row) html += "<td>" + EscapeHtml(cell) + "</td>";
      html += "</tr>\n";
    }
    html += "</table>\n";
  }
  html += "<h2>Plots</h2>\n";
  for (const ReportPlot& plot : content.plots) {
    const std::string file = "plot_" + plot.stem;
    html += "<figure><img src=\"" + file + ".svg\" alt=\"" + EscapeHtml(plot.caption) + "\"><figcaption>" +
            EscapeHtml(plot.caption) + " (<a href=\"" + file + ".png\">PNG</a>, <a href=\"" + file +
            ".pdf\">PDF</a>)</figcaption></figure>\n";
  }
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace

std::string EscapeHtml(const std::string& text) { return EscapeXml(text); }

ReportContent MakeRunReportContent(const RobotModel& model, const RunOptions& options, const RunReport& report,
                                   std::string pose_figure_png) {
  const PerBodyIdentificationResult& r = report.identification;
  ReportContent content;
  content.title = "idbench run: " + model.name() + ", " + options.motion + " motion, per-body quaternion method";
  content.command = options.command_line.empty() ? "idbench run" : options.command_line;
  content.experiment = {
      {"robot", model.name()},
      {"motion", options.motion == "paper" ? "paper: hinges 1 and 2 accelerate at " +
                                                 Format("%g", options.accel_deg_s2) + " deg/s², others locked"
                                           : options.motion == "general"
                                               ? "general: all joints move (two-harmonic Fourier series)"
                                               : "trajectory file " + options.motion},
      {"duration, step", Format("%g", options.duration) + " s, " + Format("%g", options.dt) + " s (Bullet, joint feedback)"},
      {"samples", std::to_string(r.n_samples) + " (" +
                      (options.all_samples ? std::string("every step") : [&] {
                        std::string t;
                        for (double s : options.sample_times) t += (t.empty() ? "" : ", ") + Format("%g", s);
                        return t + " s";
                      }()) + ")"},
      {"largest relative error", Format("%.3e", r.max_rel_error) + " (" + r.max_rel_error_at + "); the paper's: 3.1e-04"}};
  content.pose_figure_png = std::move(pose_figure_png);
  content.pose_caption = "The poses of " + model.name() + " along the " + options.motion + " motion (cf. the paper's Figure 2).";

  // Tables: parameters per body, then the blocks' conditioning.
  ReportTable parameters{"Identified versus true parameters (masses kg, inertias kg m²)",
                         {"body", "parameter", "true", "identified", "abs error", "rel error", "status"},
                         {}};
  ReportTable blocks{"Identifiability per body", {"body", "Newton rank", "Newton cond", "Euler rank", "Euler cond",
                                                   "Euler residual [N m]"}, {}};
  for (const BodyResult& body : r.bodies) {
    for (const ParameterResult& p : body.parameters) {
      parameters.rows.push_back({body.name, p.name, Format("%.6f", p.true_value),
                                 p.identifiable ? Format("%.12g", p.identified) : "-", Format("%.3e", p.abs_error),
                                 Format("%.2e", p.rel_error), p.identifiable ? "ok" : "NOT IDENTIFIABLE: " + p.reason});
    }
    blocks.rows.push_back({body.name, std::to_string(body.newton.rank) + "/" + std::to_string(body.newton.n_unknowns),
                           Format("%.3g", body.newton.cond),
                           std::to_string(body.euler.rank) + "/" + std::to_string(body.euler.n_unknowns),
                           Format("%.3g", body.euler.cond), Format("%.3g", body.euler.residual_norm)});
  }
  content.tables = {parameters, blocks};

  // Plots: signals, parameters, spectra, and this motion against the other one.
  const std::vector<Spectrum> spectra = RunEulerSpectra(model, report.log, report.sample_steps);
  RunOptions other = options;
  other.motion = OtherMotion(options.motion);
  const RunReport other_report = RunExperiment(model, other);
  const std::vector<MotionSummary> motions = {
      SummarizeMotion(options.motion, spectra, r.max_rel_error),
      SummarizeMotion(other.motion, RunEulerSpectra(model, other_report.log, other_report.sample_steps),
                      other_report.identification.max_rel_error)};
  content.plots = {
      {"joints", "Joint positions, velocities, accelerations and torques over time (simulated in Bullet).",
       JointSignalsPlot(SignalsOf(report.log))},
      {"parameters", "True (bars) and identified (dots, error bars = |error|) parameters; unidentifiable ones have no dot.",
       ParameterPlot("Identified versus true parameters", "true", RunParameterEstimates(r))},
      {"spectrum", "Singular values of each body's column-normalised Euler block over the samples; a missing value is "
                   "zero (a direction the motion does not excite).",
       SpectrumPlot("Singular-value spectrum of the inertia blocks", spectra)},
      {"motions", "The " + options.motion + " motion against the " + other.motion +
                      " motion with the same samples: conditioning, information (log det) and accuracy.",
       MotionComparisonPlot(motions)}};
  return content;
}

ReportContent MakeIdentifyReportContent(const RobotModel& model, const IdentifyOptions& options,
                                        const IdentifyReport& report) {
  const JointTorqueIdentification& id = report.identification;
  ReportContent content;
  content.title = "idbench identify: " + model.name() + " from " + options.data + ", " + options.estimator;
  content.command = options.command_line.empty() ? "idbench identify" : options.command_line;
  std::string friction;
  for (const std::string& f : options.friction) friction += (friction.empty() ? "" : ",") + f;
  content.experiment = {{"robot", model.name()},
                        {"data", options.data + " (" + std::to_string(report.log.n_samples()) + " samples" +
                                     (report.filtered ? ", qd and qdd estimated by zero-phase filtering" : "") + ")"},
                        {"estimator", options.estimator},
                        {"friction", friction},
                        {"cond(W)", id.linear.rank < id.base.n_base()
                                        ? "inf: rank " + std::to_string(id.linear.rank) + " of " +
                                              std::to_string(id.base.n_base()) + " (parameters not identifiable below)"
                                        : Format("%.4g", id.linear.cond)},
                        {"relative torque error (fit)", Format("%.4g", id.fit.relative_error)},
                        {"relative torque error (robot file)", Format("%.4g", id.model_fit.relative_error)}};
  if (report.validation) {
    content.experiment.push_back({"relative torque error (validation on " + options.validate + ")",
                                  Format("%.4g", report.validation->relative_error)});
  }
  // The poses along the log.
  if (report.log.n_samples() >= 2) {
    const JointLogPlayback playback(report.log);
    PoseFigureOptions figure;
    figure.times = DefaultFigureTimes(playback.duration());
    content.pose_figure_png = RenderPoseFigurePng(model, playback, figure);
    content.pose_caption = "The poses of " + model.name() + " along the log (times from its first sample).";
  }
  ReportTable base{"Base parameters (robot file value is the truth for a simulated log)",
                   {"#", "base parameter", "identified", "σ", "%σ", "status", "robot file", "difference"},
                   {}};
  std::vector<ParameterEstimate> estimates;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const std::string& name = id.base.names[static_cast<size_t>(k)];
    const std::string status = ToString(ClassifyParameter(id.beta[k], id.linear.sigma[k]));
    if (!id.linear.identifiable[static_cast<size_t>(k)]) {  // no number: the log does not determine it
      base.rows.push_back({std::to_string(k + 1), name, "-", "-", "-", status, Format("%.6g", id.beta_model[k]), "-"});
      continue;
    }
    base.rows.push_back({std::to_string(k + 1), name, Format("%.6g", id.beta[k]), Format("%.3g", id.linear.sigma[k]),
                         Format("%.3g", RelativeSigmaPercent(id.beta[k], id.linear.sigma[k])), status,
                         Format("%.6g", id.beta_model[k]),
                         Format("%.3g", id.beta[k] - id.beta_model[k])});
    estimates.push_back({std::to_string(k + 1), id.beta_model[k], id.beta[k], 3.0 * id.linear.sigma[k]});
  }
  ReportTable fit{"Torque RMS per joint [N m]", {"joint", "fit", "robot file"}, {}};
  for (Eigen::Index j = 0; j < id.fit.joint_rms.size(); ++j) {
    fit.rows.push_back({std::to_string(j + 1), Format("%.4g", id.fit.joint_rms[j]), Format("%.4g", id.model_fit.joint_rms[j])});
  }
  if (report.validation) {
    fit.header.push_back("validation");
    for (Eigen::Index j = 0; j < id.fit.joint_rms.size(); ++j) {
      fit.rows[static_cast<size_t>(j)].push_back(Format("%.4g", report.validation->joint_rms[j]));
    }
  }
  ReportTable unexcited{"Standard parameters with no effect on the torques (not identifiable)", {"parameter"}, {}};
  for (int c : id.base.unexcited) unexcited.rows.push_back({id.standard_names[static_cast<size_t>(c)]});
  content.tables = {base, fit};
  if (!unexcited.rows.empty()) content.tables.push_back(unexcited);
  const Eigen::MatrixXd W = StackBaseRegressor(model, options.friction_model(), id.base, report.log);
  content.plots = {
      {"joints", "The joint log as identified.", JointSignalsPlot(SignalsOf(report.log))},
      {"parameters", "Base parameters: robot file (bars) and identified (dots) ± 3σ; numbered as in the table.",
       ParameterPlot("Identified versus robot-file base parameters", "robot file", estimates)},
      {"spectrum", "Singular values of the column-normalised base regressor W stacked over the log.",
       SpectrumPlot("Singular-value spectrum of the base regressor", {{"W", NormalizedSingularValues(W)}})}};
  // Measured against predicted torque, τ̂ = W β of the chosen estimator, on
  // the equations the RMS numbers score (parallel-filtered as they are).
  const std::string how = " (τ̂ = W β, " + options.estimator + "): ";
  const auto filtered = [](const std::optional<ParallelFilter>& filter) {
    return filter ? "both parallel-filtered, the filter's ends dropped, as in the torque RMS." : "as in the torque RMS.";
  };
  content.plots.push_back({"torques", "Measured and predicted joint torque on the identification log" + how +
                                          filtered(report.parallel_filter),
                           TorqueComparisonPlot(PredictIdentifiedTorques(model, options, report, false),
                                                "identification log")});
  if (report.held_out_log) {
    content.plots.push_back(
        {"validation_torques", "Measured and predicted joint torque on the held-out log " + options.validate + how +
                                   filtered(report.held_out_filter),
         TorqueComparisonPlot(PredictIdentifiedTorques(model, options, report, true), "held-out log")});
  }
  return content;
}

std::vector<std::pair<std::filesystem::path, std::string>> FormatReportFiles(const ReportContent& content,
                                                                             const std::filesystem::path& dir) {
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  files.emplace_back(dir / "report.html", FormatHtml(content));
  files.emplace_back(dir / "report.pdf", FormatPdf(content));
  if (!content.pose_figure_png.empty()) files.emplace_back(dir / "figure.png", content.pose_figure_png);
  for (const ReportPlot& plot : content.plots) {
    const std::string stem = "plot_" + plot.stem;
    files.emplace_back(dir / (stem + ".png"), RenderPlot(plot.figure, PlotFormat::kPng));
    files.emplace_back(dir / (stem + ".svg"), RenderPlot(plot.figure, PlotFormat::kSvg));
    files.emplace_back(dir / (stem + ".pdf"), RenderPlot(plot.figure, PlotFormat::kPdf));
  }
  return files;
}

RunOptions RunOptionsFromResultsJson(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(source + ": not JSON: " + PrintableText(e.what(), 200));
  }
  const auto get = [&](const char* key, auto* value) {
    if (!j.contains(key)) throw std::invalid_argument(source + ": key '" + key + "': missing");
    try {
      j.at(key).get_to(*value);
    } catch (const nlohmann::json::exception&) {
      throw std::invalid_argument(source + ": key '" + key + "': wrong type");
    }
  };
  RunOptions options;
  get("robot", &options.robot);
  get("motion", &options.motion);
  if (options.motion == "paper") get("accel_deg_s2", &options.accel_deg_s2);
  get("duration", &options.duration);
  get("dt", &options.dt);
  get("sample_times", &options.sample_times);
  get("command", &options.command_line);
  size_t n_steps = 0;
  get("n_steps", &n_steps);
  options.all_samples = options.sample_times.size() == n_steps;
  if (options.all_samples) options.sample_times.clear();
  return options;
}

}  // namespace idbench
