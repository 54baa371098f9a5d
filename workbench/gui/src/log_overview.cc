// The Log tab's plot of the log: its joint positions against time (read with
// the robot and the column mapping the identification uses, streamed in
// bounded memory into a few thousand time buckets, each drawn as the band
// between its min and max with a line through the means: LogEnvelope). A
// drag across it chooses the time window (IdentifyOptions::time_window, the
// log.time_window field), a click without a drag clears it (the whole log);
// the window is drawn shaded, and the 3D view's time cursor as a dark line
// (the view replays this log while the tab is open).
#include <imgui.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/gui/log_envelope.h"
#include "idbench/gui/time_axis.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench::gui {
namespace {

constexpr Eigen::Index kMaxOverviewBuckets = 2000;  // 2000..4000 buckets once the log has as many samples
constexpr float kOverviewHeight = 96.0f;  // [px]

ImU32 JointColor(int j) {
  static const ImU32 colors[] = {IM_COL32(31, 119, 180, 255), IM_COL32(255, 127, 14, 255), IM_COL32(44, 160, 44, 255),
                                 IM_COL32(214, 39, 40, 255),  IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
                                 IM_COL32(227, 119, 194, 255)};
  return colors[j % 7];
}

}  // namespace

void GuiApp::Impl::CollectLogOverview(bool wait) {
  std::function<void()> apply;
  std::string error;
  if (!(wait ? overview_job.Wait(&apply, &error) : overview_job.Collect(&apply, &error))) return;
  if (apply) apply();
  overview_error = error;
}

void GuiApp::Impl::DrawLogOverview() {
  IdentifyOptions& id = session.identify;
  // Read again when the log, the robot or the column mapping change.
  std::string key = id.data + "\n" + session.robot_source() + "\n" + id.format.angle_unit;
  for (const std::string& column : id.format.columns) key += "," + column;
  if (key != overview_key) {
    overview_key = key;
    overview_job.RequestStop();  // a read of the previous log ends at its next chunk
    CollectLogOverview(true);
    overview = LogEnvelope(kMaxOverviewBuckets);
    overview_mean.resize(0, 0);
    overview_error.clear();
    if (!id.data.empty()) {
      overview_job.Start([this, data = id.data, model = session.model(),
                          format = id.format](const std::atomic<bool>& stop) -> std::function<void()> {
        const std::unique_ptr<JointLogSource> source = OpenJointLog(data, model, format, TorqueColumns::kOptional);
        // Streamed, in bounded memory whatever the log's length (LogEnvelope:
        // 2 kMaxOverviewBuckets buckets at most, 3 + 3 n_dof doubles each).
        LogEnvelope envelope(kMaxOverviewBuckets);
        if (!FoldJointPositions(*source, stop, &envelope)) return nullptr;  // superseded: nothing to show
        if (envelope.n_samples() < 2) throw std::invalid_argument(data + ": fewer than two samples");
        return [this, envelope = std::move(envelope)]() mutable {
          overview_mean = envelope.Mean();
          overview = std::move(envelope);
        };
      });
    }
  }
  CollectLogOverview(false);
  if (!id.data.empty() && overview_job.running()) {
    ImGui::TextColored(kDimColor, "Reading %s for its plot ...", id.data.c_str());
    return;
  }
  if (id.data.empty()) return;
  if (overview.n_samples() < 2) {
    ImGui::TextColored(kDimColor, "No plot of the log: %s", overview_error.c_str());
    return;
  }

  // The plot, an invisible button that takes the drag.
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 size(std::max(100.0f, ImGui::GetContentRegionAvail().x), kOverviewHeight);
  ImGui::InvisibleButton("##log.overview", size);
  const ImVec2 p1(p0.x + size.x, p0.y + size.y);
  const double t_first = overview.t_begin(0), t_last = overview.t_end(overview.n_buckets() - 1);
  const TimeAxis axis{.x0 = p0.x, .x1 = p1.x, .t0 = t_first, .t1 = t_last};
  const ImGuiIO& io = ImGui::GetIO();
  std::vector<double> window = id.time_window;
  if (ImGui::IsItemActive() || ImGui::IsItemDeactivated()) {
    window = DraggedTimeWindow(axis, io.MouseClickedPos[0].x, io.MousePos.x);
    if (ImGui::IsItemDeactivated()) {  // released: the window the identification uses
      id.time_window = window;
      time_window_text = JoinNumbers(window);
      text_error.clear();
    }
  }
  widgets.Record("log.overview");

  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(p0, p1, IM_COL32(252, 252, 252, 255));
  if (window.size() == 2) {  // the time window, shaded
    const float a = static_cast<float>(std::clamp(axis.PixelAt(window[0]), axis.x0, axis.x1));
    const float b = static_cast<float>(std::clamp(axis.PixelAt(window[1]), axis.x0, axis.x1));
    draw->AddRectFilled(ImVec2(a, p0.y), ImVec2(b, p1.y), IM_COL32(70, 130, 230, 60));
    draw->AddLine(ImVec2(a, p0.y), ImVec2(a, p1.y), IM_COL32(70, 130, 230, 200));
    draw->AddLine(ImVec2(b, p0.y), ImVec2(b, p1.y), IM_COL32(70, 130, 230, 200));
  }
  draw->AddRect(p0, p1, IM_COL32(150, 150, 160, 255));
  if (ReplaysLog()) {  // the 3D view's instant: the robot there is as logged at this t
    const float x = static_cast<float>(std::clamp(axis.PixelAt(t), axis.x0, axis.x1));
    draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), IM_COL32(20, 20, 20, 220), 1.5f);
  }
  const double lo = overview.min().minCoeff(), hi = overview.max().maxCoeff();
  const double span = hi > lo ? hi - lo : 1.0;
  const float top = p0.y + 16.0f, height = size.y - 20.0f;
  auto y_at = [&](double q) { return top + static_cast<float>((hi - q) / span) * height; };
  const Eigen::Index n = overview.n_buckets();
  std::vector<float> x_mid(static_cast<size_t>(n));  // [px] each bucket's middle
  for (Eigen::Index k = 0; k < n; ++k)
    x_mid[static_cast<size_t>(k)] = static_cast<float>(axis.PixelAt(0.5 * (overview.t_begin(k) + overview.t_end(k))));
  std::vector<ImVec2> points(static_cast<size_t>(n));
  for (Eigen::Index j = 0; j < overview.n_channels(); ++j) {
    const ImU32 color = JointColor(static_cast<int>(j));
    // The envelope: per pixel column, the min and max of the buckets whose
    // middle falls in it, filled (at least a pixel high).
    const ImU32 band = (color & ~IM_COL32_A_MASK) | IM_COL32(0, 0, 0, 110);
    for (Eigen::Index k = 0; k < n;) {
      const float x = std::floor(x_mid[static_cast<size_t>(k)]);
      double q_min = overview.min()(k, j), q_max = overview.max()(k, j);
      for (++k; k < n && std::floor(x_mid[static_cast<size_t>(k)]) == x; ++k)
        q_min = std::min(q_min, overview.min()(k, j)), q_max = std::max(q_max, overview.max()(k, j));
      draw->AddRectFilled(ImVec2(x, y_at(q_max)), ImVec2(x + 1.0f, y_at(q_min) + 1.0f), band);
    }
    // The line through the buckets' means, at their middles.
    for (Eigen::Index k = 0; k < n; ++k)
      points[static_cast<size_t>(k)] = ImVec2(x_mid[static_cast<size_t>(k)], y_at(overview_mean(k, j)));
    draw->AddPolyline(points.data(), static_cast<int>(n), color, 0, 1.0f);
  }
  char text[200];
  std::snprintf(text, sizeof text, "q [rad] against t, %.4g to %.4g s; drag to choose the time window%s",
                t_first, t_last, window.size() == 2 ? "" : " (now: all of it)");
  draw->AddText(ImVec2(p0.x + 4.0f, p0.y + 1.0f), IM_COL32(90, 90, 90, 255), text);
}

}  // namespace idbench::gui
