// The Log tab: a robot's URDF and a recorded joint log (fields with their
// recent files, or files dropped onto the window), a preview of the log's first rows with the column
// mapping, the friction terms and the estimator, a held-out log, a plot of
// the log on which a drag chooses the time window; Identify runs
// `idbench identify`'s library call on session.identify (the same options
// struct, so the same numbers) on a worker thread, with a progress bar and
// Cancel (log.cancel), then shows measured against predicted torque
// per joint (or their residuals), the parameter table with σ and status, and the physically
// consistent fit's verdict. Export is in the Export tab (export.urdf).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/gui/recent_files_settings.h"

namespace idbench::gui {
namespace {

const ImVec4 kGoodColor(0.10f, 0.55f, 0.20f, 1.0f);
constexpr int kPreviewRows = 3;  // data rows under the header

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (!item.empty()) items.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

std::string JoinList(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
  return text;
}

// Parses a column list into format->columns; false with *why as the library says it.
bool ParseColumns(const std::string& text, JointLogFormat* format, std::string* why) {
  JointLogFormat parsed = *format;
  parsed.columns = SplitList(text);
  try {
    ExpandColumnNames(parsed.columns);
  } catch (const std::invalid_argument& e) {
    *why = e.what();
    return false;
  }
  if (!parsed.IsValid(why)) return false;
  *format = parsed;
  return true;
}

bool ParseFriction(const std::string& text, std::vector<std::string>* friction, std::string* why) {
  const std::vector<std::string> terms = SplitList(text);
  if (!ParseFrictionTerms(terms, why)) return false;
  *friction = terms;
  return true;
}

// A list of numbers ("" = none); `count` > 0: exactly that many.
bool ParseNumbers(const std::string& text, size_t count, std::vector<double>* values, std::string* why) {
  std::vector<double> parsed;
  for (const std::string& item : SplitList(text)) {
    double v = 0.0;
    if (!internal::ParseDouble(item, &v, why)) return false;
    parsed.push_back(v);
  }
  if (count > 0 && !parsed.empty() && parsed.size() != count) {
    *why = "expected " + std::to_string(count) + " numbers or none, got " + std::to_string(parsed.size());
    return false;
  }
  *values = parsed;
  return true;
}

// The first lines of a text log, split at commas; a bag or an unreadable file gives none.
std::vector<std::vector<std::string>> ReadPreview(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::error_code error;
  if (path.empty() || !std::filesystem::is_regular_file(path, error)) return rows;
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".db3" || ext == ".mcap" || ext == ".yaml") return rows;
  std::ifstream in(path);
  std::string line;
  while (static_cast<int>(rows.size()) <= kPreviewRows && std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    size_t start = 0;
    for (size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      cells.push_back(line.substr(start, comma - start));
    cells.push_back(line.substr(start));
    rows.push_back(std::move(cells));
  }
  return rows;
}

// One joint's measured (light) and predicted (orange) torque against time, or
// (residual) the residual measured − predicted (red), in a box of `size`.
void TorquePlot(const char* label, const TorqueSeries& series, int joint, bool residual, ImVec2 size) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton(label, size);
  const ImVec2 p1(p0.x + size.x, p0.y + size.y);
  draw->AddRectFilled(p0, p1, IM_COL32(25, 25, 30, 255));
  draw->AddRect(p0, p1, IM_COL32(90, 90, 100, 255));
  const Eigen::Index n = series.t.size();
  if (n < 2) return;
  const Eigen::VectorXd measured = series.measured.col(joint), predicted = series.predicted.col(joint);
  const Eigen::VectorXd error = measured - predicted;
  std::vector<std::pair<const Eigen::VectorXd*, ImU32>> lines;
  if (residual) lines = {{&error, IM_COL32(255, 90, 90, 255)}};
  else lines = {{&measured, IM_COL32(220, 220, 220, 255)}, {&predicted, IM_COL32(255, 150, 40, 255)}};
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& [values, color] : lines) {
    lo = std::min(lo, values->minCoeff());
    hi = std::max(hi, values->maxCoeff());
  }
  const double span = hi > lo ? hi - lo : 1.0;
  const double t0 = series.t[0], t1 = series.t[n - 1] > t0 ? series.t[n - 1] : t0 + 1.0;
  const float top = p0.y + 14.0f, height = size.y - 18.0f;
  auto point = [&](Eigen::Index k, double v) {
    return ImVec2(p0.x + 2.0f + static_cast<float>((series.t[k] - t0) / (t1 - t0)) * (size.x - 4.0f),
                  top + static_cast<float>((hi - v) / span) * height);
  };
  // At most ~2 points per pixel.
  const Eigen::Index step = std::max<Eigen::Index>(1, n / static_cast<Eigen::Index>(2 * size.x));
  for (const auto& [values, color] : lines) {
    std::vector<ImVec2> points;
    for (Eigen::Index k = 0; k < n; k += step) points.push_back(point(k, (*values)[k]));
    draw->AddPolyline(points.data(), static_cast<int>(points.size()), color, 0, 1.0f);
  }
  char text[160];
  const double rms = std::sqrt(error.squaredNorm() / static_cast<double>(n));
  std::snprintf(text, sizeof text, "%s  [%.3g, %.3g] N m  rms %.3g", label, lo, hi, rms);
  draw->AddText(ImVec2(p0.x + 4.0f, p0.y + 1.0f), IM_COL32(200, 200, 200, 255), text);
}

}  // namespace

void GuiApp::Impl::DrawLogTab() {
  IdentifyOptions& id = session.identify;
  const bool busy = session.any_running();
  if (!log_fields_initialised) {  // the text fields start at the options' values
    friction_text = JoinList(id.friction);
    columns_text = JoinList(id.format.columns);
    time_window_text = JoinNumbers(id.time_window);
    drive_gains_text = JoinNumbers(id.format.drive_gains);
    more_data_text = JoinList(id.more_data);
    log_fields_initialised = true;
  }
  ImGui::BeginDisabled(busy);
  ImGui::PushItemWidth(-110);
  // The robot: a URDF loaded on Enter, on Load, when picked from the recent
  // files, or when set by a script.
  RecentFilesCombo("log.robot", [this](const std::string& path) {
    log_robot_path = path;
    pending_robot = path;
  });
  ImGui::SameLine(0, 2);
  if (ImGui::InputText("robot URDF##log.robot", &log_robot_path, ImGuiInputTextFlags_EnterReturnsTrue))
    pending_robot = log_robot_path;
  widgets.Record("log.robot", [this](const std::string& text, std::string*) {
    log_robot_path = text;
    pending_robot = text;
    return true;
  });
  RecentFilesCombo("log.data", [&id](const std::string& path) { id.data = path; });
  ImGui::SameLine(0, 2);
  widgets.InputText("log.data", "log", &id.data);
  RecentFilesCombo("log.validate", [&id](const std::string& path) { id.validate = path; });
  ImGui::SameLine(0, 2);
  widgets.InputText("log.validate", "held-out log", &id.validate);
  // More logs of the robot, identified together with the first (--data A --data B).
  if (ImGui::InputText("more logs##log.more_data", &more_data_text)) id.more_data = SplitPaths(more_data_text);
  widgets.Record("log.more_data", [this, &id](const std::string& text, std::string*) {
    more_data_text = text;
    id.more_data = SplitPaths(text);
    return true;
  });
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Other logs of this robot, comma-separated, each read, windowed and filtered as the log: their "
                      "equations are stacked with its own; empty: the log alone");
  }
  // Option lists: parsed when the field is left, or by a script's set.
  auto list_field = [&](const char* name, const char* label, std::string* text, auto parse) {
    ImGui::InputText((std::string(label) + "##" + name).c_str(), text);
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      std::string why;
      text_error = parse(*text, &why) ? "" : std::string(name) + ": " + why;
    }
    widgets.Record(name, [text, parse](const std::string& value, std::string* why) {
      if (!parse(value, why)) return false;
      *text = value;
      return true;
    });
  };
  list_field("log.columns", "columns", &columns_text,
             [&id](const std::string& text, std::string* why) { return ParseColumns(text, &id.format, why); });
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The file's columns in order: t, q1..qN, qd1.., qdd1.., tau1.., i1.. (currents), _ to skip.\n"
                      "Empty: the header names them.");
  list_field("log.friction", "friction", &friction_text,
             [&id](const std::string& text, std::string* why) { return ParseFriction(text, &id.friction, why); });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("of: none, viscous, coulomb, offset, rotor");
  list_field("log.time_window", "time window [s]", &time_window_text, [&id](const std::string& text, std::string* why) {
    return ParseNumbers(text, 2, &id.time_window, why);
  });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("T0,T1: the part of the log identified from; empty: all of it");
  list_field("log.drive_gains", "drive gains [N m/A]", &drive_gains_text,
             [&id](const std::string& text, std::string* why) {
               return ParseNumbers(text, 0, &id.format.drive_gains, why);
             });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One per joint, tau = K i from the current columns i1..; empty: the log's tau");
  ImGui::PopItemWidth();
  ImGui::SetNextItemWidth(80);
  widgets.Combo("log.estimator", "estimator", &id.estimator, kTorqueEstimatorNames);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  widgets.Combo("log.angle_unit", "angle unit", &id.format.angle_unit, {"rad", "deg"});
  ImGui::SameLine();
  widgets.Checkbox("log.torque_held", "torque held", &id.format.torque_held);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("The logged torques are commands held to the next sample (a controller's zero-order hold)");
  }
  // Coulomb's sign near rest (identify --coulomb-smoothing, --coulomb-min-speed),
  // on a row of their own (Identify follows them).
  if (std::find(id.friction.begin(), id.friction.end(), "coulomb") != id.friction.end()) {
    ImGui::SetNextItemWidth(45);
    widgets.InputDouble("log.coulomb_smoothing", "Fc v", &id.coulomb_smoothing);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Coulomb smoothing v [rad/s]: Fc tanh(qd/v) for Fc sign(qd); 0: the sign");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(45);
    widgets.InputDouble("log.coulomb_min_speed", "Fc V", &id.coulomb_min_speed);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Coulomb min speed V [rad/s]: no Fc term where |qd| < V; 0: off");
  }
  // What the closed-loop estimators re-simulate (iv, didim).
  if (IsClosedLoopEstimator(id.estimator)) {
    ImGui::PushItemWidth(-110);
    widgets.InputText("log.controller", "controller file", &id.controller);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("The robot's controller: {\"kp\": [...], \"kd\": [...], \"ki\": [...], \"tau_max\": [...], "
                        "\"feedforward\": \"model\"}");
    }
    widgets.InputText("log.reference", "reference", &id.reference);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The motion the controller tracked: a built-in motion or a trajectory file");
    ImGui::PopItemWidth();
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  const bool identifying = session.running(JobKind::kIdentify);
  if (widgets.Button("log.identify", "Identify", !busy && !id.data.empty())) session.StartIdentify();
  ImGui::SameLine();
  if (widgets.Button("log.cancel", "Cancel", identifying)) session.CancelIdentify();
  if (identifying) {  // how far it is, and what it does
    const IdentifyProgress progress = session.identify_progress();
    ImGui::SameLine();
    ImGui::ProgressBar(static_cast<float>(progress.fraction), ImVec2(-1, 0), progress.stage.c_str());
    widgets.Record("log.progress");
  }
  if (!text_error.empty()) ImGui::TextColored(kErrorColor, "%s", text_error.c_str());
  DrawLogResults();
}

// The log itself, the first tab under the results: its first rows and its
// plot (where the time window is dragged).
void GuiApp::Impl::DrawLogDataTab() {
  const bool open = ImGui::BeginTabItem("Log");
  widgets.Record("tab.log.data");
  if (!open) return;
  DrawLogPreview();
  ImGui::BeginDisabled(session.any_running());
  DrawLogOverview();
  ImGui::EndDisabled();
  ImGui::EndTabItem();
}

// A path the user has settled on (typed, picked, dropped, set by a script or
// the command line) joins the field's recent files when it exists, as an
// absolute path. Called every frame (GuiApp::Frame), whichever tab is open.
void GuiApp::Impl::NoteRecentFile(const std::string& field, const std::string& path, bool editing) {
  std::string& noted = recent_noted[field];
  if (editing || path == noted) return;
  noted = path;
  std::error_code error;
  if (path.empty() || !std::filesystem::exists(path, error)) return;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  recent_files.Add(field, error ? path : absolute.lexically_normal().string());
  MarkRecentFilesChanged();
}

// An arrow before a path field listing its recent files, newest first; a
// script picks one by its place (`set log.data.recent 1` for the newest).
void GuiApp::Impl::RecentFilesCombo(const std::string& field, const std::function<void(const std::string&)>& pick) {
  const std::vector<std::string>& paths = recent_files.Get(field);
  ImGui::BeginDisabled(paths.empty());
  if (ImGui::BeginCombo(("##" + field + ".recent").c_str(), nullptr, ImGuiComboFlags_NoPreview)) {
    for (const std::string& path : paths)
      if (ImGui::Selectable(path.c_str())) pick(path);
    ImGui::EndCombo();
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(paths.empty() ? "no recent files yet" : "recent files");
  widgets.Record(field + ".recent", [this, field, pick](const std::string& text, std::string* why) {
    const std::vector<std::string>& list = recent_files.Get(field);
    long long k = 0;
    if (list.empty()) {
      *why = "no recent files yet";
      return false;
    }
    if (!internal::ParseInt(text, 1, static_cast<long long>(list.size()), &k, why)) return false;
    pick(list[static_cast<size_t>(k - 1)]);
    return true;
  });
}

// The first rows of the log under its header, with the names the columns are read as.
void GuiApp::Impl::DrawLogPreview() {
  const std::string& path = session.identify.data;
  if (path != preview_path) {
    preview_path = path;
    preview_rows = ReadPreview(path);
  }
  if (preview_rows.empty()) {
    ImGui::TextColored(kDimColor, path.empty() ? "No log: type its path or drop the file onto the window."
                                               : "No preview of this log (a bag, or not readable as text).");
    return;
  }
  const std::vector<std::string>& header = preview_rows.front();
  const int n_columns = static_cast<int>(std::min<size_t>(header.size(), 63));
  std::vector<std::string> mapping;
  try {
    mapping = ExpandColumnNames(session.identify.format.columns);
  } catch (const std::invalid_argument&) {
  }
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingFixedFit;
  const float height = ImGui::GetTextLineHeightWithSpacing() * (kPreviewRows + 2.6f);
  if (ImGui::BeginTable("log_preview", n_columns, flags, ImVec2(0, height))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (int c = 0; c < n_columns; ++c) {
      // "header → name read as" where the column list renames it.
      const std::string& name = header[static_cast<size_t>(c)];
      const bool renamed = c < static_cast<int>(mapping.size()) && mapping[static_cast<size_t>(c)] != name;
      ImGui::TableSetupColumn((renamed ? name + " > " + mapping[static_cast<size_t>(c)] : name).c_str());
    }
    ImGui::TableHeadersRow();
    for (size_t r = 1; r < preview_rows.size(); ++r) {
      ImGui::TableNextRow();
      for (int c = 0; c < n_columns && c < static_cast<int>(preview_rows[r].size()); ++c) {
        ImGui::TableSetColumnIndex(c);
        ImGui::TextUnformatted(preview_rows[r][static_cast<size_t>(c)].c_str());
      }
    }
    ImGui::EndTable();
  }
  widgets.Record("log.preview");
}

// The identification: errors, the pc verdict, then torque plots, the
// parameter table or the bounds the pc estimate sits on.
void GuiApp::Impl::DrawLogResults() {
  const auto& report = session.identify_report();
  // An identification that has just finished shows its torques.
  const bool identifying = session.running(JobKind::kIdentify);
  const bool show_torques = was_identifying && !identifying && report;
  was_identifying = identifying;
  if (!report) {
    ImGui::TextColored(kDimColor, "Nothing identified yet.");
    if (ImGui::BeginTabBar("log_results")) {
      DrawLogDataTab();
      ImGui::EndTabBar();
    }
    return;
  }
  const JointTorqueIdentification& ident = report->identification;
  const IdentifyOptions& options = session.identified_with();
  ImGui::Text("%s: %lld samples, torque error %.3g%% (robot file %.3g%%)",
              std::filesystem::path(options.data).filename().c_str(), static_cast<long long>(report->n_samples),
              100 * ident.fit.relative_error, 100 * ident.model_fit.relative_error);
  if (report->validation) {
    ImGui::SameLine();
    ImGui::Text("; held out %.3g%%", 100 * report->validation->relative_error);
  }
  // The verdict of the physically consistent estimate, and what it rests on.
  const IdentificationVerdict& verdict = ident.verdict;
  ImGui::TextColored(verdict.fit_to_load() ? kGoodColor : kErrorColor, "pc: %s", ToKey(verdict.status));
  ImGui::SameLine();
  ImGui::TextWrapped("%s", verdict.message.c_str());
  widgets.Record("log.verdict");
  if (!verdict.fit_to_load())
    ImGui::TextWrapped("%s", verdict.cause.c_str());
  const std::vector<ActiveBound>& bounds = ident.consistent.bounds_at_optimum;
  if (ImGui::BeginTabBar("log_results")) {
    DrawLogDataTab();
    const bool torques =
        ImGui::BeginTabItem("Torques", nullptr, show_torques ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None);
    widgets.Record("tab.log.torques");
    if (torques) {
      DrawTorquePlots();
      ImGui::EndTabItem();
    }
    const bool parameters = ImGui::BeginTabItem("Parameters");
    widgets.Record("tab.log.parameters");
    if (parameters) {
      // How σ was computed (batch means, n_eff), as identify prints it under its table.
      ImGui::TextColored(kDimColor, "%s", SigmaMethodText(ident.linear).c_str());
      const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                    ImGuiTableFlags_Resizable;
      if (ImGui::BeginTable("log_parameters", 6, flags, ImVec2(0, ImGui::GetContentRegionAvail().y))) {
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableSetupColumn("base parameter", ImGuiTableColumnFlags_WidthStretch);
        for (const char* c : {"robot file", "identified", "σ", "%σ", "status"})
          ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthFixed, 0.0f);
        ImGui::TableHeadersRow();
        for (int k = 0; k < ident.base.n_base(); ++k) {
          const bool identifiable = ident.linear.identifiable[static_cast<size_t>(k)];
          const ParameterStatus status = ClassifyParameter(ident.beta[k], ident.linear.sigma[k]);
          const ImVec4* color = status == ParameterStatus::kPoor || !identifiable           ? &kErrorColor
                                : status == ParameterStatus::kIndistinguishableFromZero ? &kDimColor
                                                                                         : nullptr;
          ImGui::TableNextRow();
          ImGui::TableSetColumnIndex(0);
          TextCell(ident.base.names[static_cast<size_t>(k)], color);
          ImGui::TableSetColumnIndex(1);
          TextCell(Number(ident.beta_model[k], "%.5g"), color);
          ImGui::TableSetColumnIndex(2);
          TextCell(identifiable ? Number(ident.beta[k], "%.5g") : "-", color);
          ImGui::TableSetColumnIndex(3);
          TextCell(identifiable ? Number(ident.linear.sigma[k], "%.2g") : "-", color);
          ImGui::TableSetColumnIndex(4);
          TextCell(identifiable ? Number(RelativeSigmaPercent(ident.beta[k], ident.linear.sigma[k]), "%.2g") : "-",
                   color);
          ImGui::TableSetColumnIndex(5);
          TextCell(ToString(status), color);
        }
        ImGui::EndTable();
      }
      ImGui::EndTabItem();
    }
    // What the physically consistent estimate sits on.
    const std::string bounds_label = "On a bound (" + std::to_string(bounds.size()) + ")###bounds";
    const bool on_bounds = ImGui::BeginTabItem(bounds_label.c_str());
    widgets.Record("tab.log.bounds");
    if (on_bounds) {
      if (bounds.empty()) ImGui::TextColored(kDimColor, "No bound is active at the optimum.");
      for (const ActiveBound& b : bounds) ImGui::BulletText("%s", b.text.c_str());
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
}

// Measured against predicted torque per joint, two columns of plots.
void GuiApp::Impl::DrawTorquePlots() {
  if (session.held_out_torques()) {
    widgets.Checkbox("log.plot_held_out", "held-out log", &plot_held_out);
    ImGui::SameLine();
  } else {
    plot_held_out = false;
  }
  widgets.Checkbox("log.plot_residuals", "residuals", &plot_residuals);
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, plot_residuals ? "residual: measured - predicted torque [N m] against time"
                                               : "measured (light) and predicted (orange) torque [N m] against time");
  const std::optional<TorqueSeries>& series = plot_held_out ? session.held_out_torques() : session.fit_torques();
  if (!series) return;
  const int n_dof = static_cast<int>(series->measured.cols());
  const int rows = (n_dof + 1) / 2;
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const ImVec2 size(0.5f * (avail.x - ImGui::GetStyle().ItemSpacing.x),
                    std::max(40.0f, (avail.y - spacing * static_cast<float>(rows)) / static_cast<float>(rows)));
  for (int j = 0; j < n_dof; ++j) {
    if (j % 2 == 1) ImGui::SameLine();
    const std::string name = j < session.model().n_dof() ? session.model().link(j).joint_name : std::to_string(j + 1);
    TorquePlot(name.c_str(), *series, j, plot_residuals, size);
    widgets.Record("log.plot." + std::to_string(j + 1));
  }
}

}  // namespace idbench::gui
