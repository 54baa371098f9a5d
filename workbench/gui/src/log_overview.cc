// The Log tab's plot of the log: its joint positions against time (read with
// the robot and the column mapping the identification uses, decimated to a
// few thousand points, streamed in bounded memory). A drag across it chooses the time window
// (IdentifyOptions::time_window, the log.time_window field), a click without
// a drag clears it (the whole log); the window is drawn shaded.
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
#include "idbench/gui/time_axis.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench::gui {
namespace {

constexpr Eigen::Index kMaxOverviewPoints = 2000;  // 2000..4000 points drawn
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
    overview_t.resize(0);
    overview_q.resize(0, 0);
    overview_error.clear();
    if (!id.data.empty()) {
      overview_job.Start([this, data = id.data, model = session.model(),
                          format = id.format](const std::atomic<bool>& stop) -> std::function<void()> {
        const std::unique_ptr<JointLogSource> source = OpenJointLog(data, model, format, TorqueColumns::kOptional);
        // Streamed, in bounded memory whatever the log's length: every
        // stride-th sample is kept; when 2 kMaxOverviewPoints are held, every
        // other one is dropped and the stride doubles. The last sample too.
        std::vector<double> t;
        std::vector<Eigen::VectorXd> q;
        Eigen::Index stride = 1, index = 0, n_dof = 0;
        double t_first = 0.0, t_last = 0.0;
        Eigen::VectorXd q_last;
        JointLogChunk chunk;
        while (!stop && source->Next(4096, &chunk))
          for (Eigen::Index k = 0; k < chunk.samples.t.size(); ++k, ++index) {
            if (index == 0) t_first = chunk.samples.t[k], n_dof = chunk.samples.q.cols();
            t_last = chunk.samples.t[k];
            q_last = chunk.samples.q.row(k).transpose();
            if (index % stride != 0) continue;
            t.push_back(t_last);
            q.push_back(q_last);
            if (static_cast<Eigen::Index>(t.size()) == 2 * kMaxOverviewPoints) {
              for (size_t r = 0; 2 * r < t.size(); ++r) t[r] = t[2 * r], q[r] = q[2 * r];
              t.resize(t.size() / 2), q.resize(q.size() / 2);
              stride *= 2;
            }
          }
        if (stop) return nullptr;  // superseded: nothing to show
        if (index < 2) throw std::invalid_argument(data + ": fewer than two samples");
        if (t.back() != t_last) t.push_back(t_last), q.push_back(q_last);
        Eigen::MatrixXd q_kept(static_cast<Eigen::Index>(t.size()), n_dof);
        for (size_t r = 0; r < q.size(); ++r) q_kept.row(static_cast<Eigen::Index>(r)) = q[r].transpose();
        return [this, t_kept = Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()))),
                q_kept = std::move(q_kept), t_first, t_last]() mutable {
          overview_t = std::move(t_kept);
          overview_q = std::move(q_kept);
          overview_t_first = t_first;
          overview_t_last = t_last;
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
  if (overview_t.size() < 2) {
    ImGui::TextColored(kDimColor, "No plot of the log: %s", overview_error.c_str());
    return;
  }

  // The plot, an invisible button that takes the drag.
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 size(std::max(100.0f, ImGui::GetContentRegionAvail().x), kOverviewHeight);
  ImGui::InvisibleButton("##log.overview", size);
  const ImVec2 p1(p0.x + size.x, p0.y + size.y);
  const TimeAxis axis{.x0 = p0.x, .x1 = p1.x, .t0 = overview_t_first, .t1 = overview_t_last};
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
  const double lo = overview_q.minCoeff(), hi = overview_q.maxCoeff();
  const double span = hi > lo ? hi - lo : 1.0;
  const float top = p0.y + 16.0f, height = size.y - 20.0f;
  std::vector<ImVec2> points(static_cast<size_t>(overview_t.size()));
  for (Eigen::Index j = 0; j < overview_q.cols(); ++j) {
    for (Eigen::Index k = 0; k < overview_t.size(); ++k)
      points[static_cast<size_t>(k)] = ImVec2(static_cast<float>(axis.PixelAt(overview_t[k])),
                                              top + static_cast<float>((hi - overview_q(k, j)) / span) * height);
    draw->AddPolyline(points.data(), static_cast<int>(points.size()), JointColor(static_cast<int>(j)), 0, 1.0f);
  }
  char text[200];
  std::snprintf(text, sizeof text, "q [rad] against t, %.4g to %.4g s; drag to choose the time window%s",
                overview_t_first, overview_t_last,
                window.size() == 2 ? "" : " (now: all of it)");
  draw->AddText(ImVec2(p0.x + 4.0f, p0.y + 1.0f), IM_COL32(90, 90, 90, 255), text);
}

}  // namespace idbench::gui
