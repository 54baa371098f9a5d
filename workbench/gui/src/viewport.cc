// The 3D view and its timeline: the robot at the shown instant of the current
// motion, drawn into the renderer's texture only when something changed;
// mouse orbit, pan and zoom; play/pause, speed, overlays and a scrubber.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "gui_app_impl.h"
#include "gui_helpers.h"
#include "idbench/engine/kinematics.h"
#include "idbench/render/camera.h"
#include "idbench/render/robot_scene.h"
#include "idbench/render/scene_renderer.h"
#include "idbench/workbench/formats/scene_file.h"

namespace idbench::gui {

double GuiApp::Impl::TimelineStart() const { return ReplaysLog() ? overview.t_begin(0) : 0.0; }

double GuiApp::Impl::TimelineEnd() const {
  if (ReplaysLog()) return overview.t_end(overview.n_buckets() - 1);
  const Trajectory* motion = session.current_motion();
  return motion ? motion->duration() : 0.0;
}

Eigen::VectorXd GuiApp::Impl::QAt(double time) const {
  if (ReplaysLog()) {
    // The buckets' means at their middles (one sample per bucket up to
    // kMaxOverviewBuckets samples: the log's own q), linear between them.
    const Eigen::Index n = overview.n_buckets();
    auto middle = [&](Eigen::Index k) { return 0.5 * (overview.t_begin(k) + overview.t_end(k)); };
    if (time <= middle(0)) return overview_mean.row(0).transpose();
    if (time >= middle(n - 1)) return overview_mean.row(n - 1).transpose();
    Eigen::Index lo = 0, hi = n - 1;  // middle(lo) < time <= middle(hi)
    while (hi - lo > 1) {
      const Eigen::Index mid = (lo + hi) / 2;
      (middle(mid) < time ? lo : hi) = mid;
    }
    const double a = (time - middle(lo)) / (middle(hi) - middle(lo));
    return ((1.0 - a) * overview_mean.row(lo) + a * overview_mean.row(hi)).transpose();
  }
  const Trajectory* motion = session.current_motion();
  if (!motion) return Eigen::VectorXd::Zero(session.model().n_dof());
  return motion->At(std::clamp(time, 0.0, motion->duration())).q;
}

// Rebuilds the built-in motion when its name or duration was edited (by a
// widget or a script), and keeps the timeline inside the shown source.
void GuiApp::Impl::SyncMotion() {
  const std::string key = session.motion + "/" + std::to_string(session.builtin_duration);
  if (key != shown_motion_key) {
    if (session.motion != "designed" || session.design_report()) session.SelectMotion(session.motion);
    shown_motion_key = key;
  }
  if (ReplaysLog() || session.current_motion()) t = std::clamp(t, TimelineStart(), TimelineEnd());
}

// Reads the cell again when design.scene was edited (an unreadable or
// invalid file: its error in the messages, no obstacles drawn), and refits
// the view when the cell or the mounting changed.
void GuiApp::Impl::SyncScene() {
  const std::array<double, 6>& base_pose = session.design.design.base_pose.xyz_rpy;
  if (!scene_dirty && base_pose == drawn_base_pose) return;
  if (scene_dirty) {
    cell = Cell();
    try {
      if (!session.design.scene.empty()) cell = ReadSceneFile(session.design.scene);
    } catch (const std::exception& e) {
      session.Error(std::string("design.scene: ") + e.what());
    }
    scene_dirty = false;
  }
  drawn_base_pose = base_pose;
  fitted_motion_version = -1;
  drawn_once = false;
}

// The robot's extent over the whole motion, so that the camera does not jump
// while it plays, and the cell's obstacles beside it.
void GuiApp::Impl::FitView() {
  const RobotModel& model = session.model();
  const bool shows_motion = ReplaysLog() || session.current_motion();
  const Eigen::Isometry3d X_WR = session.design.design.base_pose.X_WR();
  RobotData data(model);
  motion_points_W.clear();
  const int n_poses = shows_motion ? 9 : 1;
  for (int k = 0; k < n_poses; ++k) {
    const double t0 = TimelineStart(), t1 = TimelineEnd();
    const Eigen::VectorXd q = shows_motion ? QAt(t0 + (t1 - t0) * k / (n_poses - 1))
                                           : Eigen::VectorXd::Zero(model.n_dof());
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
    ComputeKinematics(model, q, zero, zero, &data);
    const std::vector<Eigen::Vector3d> points = BuildRobotScene(model, data, X_WR).BoundingPoints();
    motion_points_W.insert(motion_points_W.end(), points.begin(), points.end());
  }
  Eigen::Vector3d lo = motion_points_W.front(), hi = lo;
  for (const Eigen::Vector3d& p : motion_points_W) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  robot_size = std::max((hi - lo).norm(), 1e-3);
  Scene obstacles;
  AddCellObstacles(cell, &obstacles);
  const std::vector<Eigen::Vector3d> near = CellPointsNearRobot(obstacles, motion_points_W);
  motion_points_W.insert(motion_points_W.end(), near.begin(), near.end());
  floor = FitFloor(motion_points_W);
  fitted_motion_version = session.motion_version();
  fitted_source = ShownSource();
}

// Markers on demand, sized by the robot and long enough to stick out of the
// (solid) links: every link frame's axes from its hinge point (x red, y green,
// z blue), and a dark cross of three sticks through every centre of mass.
void GuiApp::Impl::AddOverlays(const RobotModel& model, const RobotData& data, Scene* scene) const {
  const Eigen::Isometry3d X_WR = session.design.design.base_pose.X_WR();
  auto stick = [&](const Eigen::Vector3d& p_W, const Eigen::Vector3d& e_W, double length, const Eigen::Vector3f& color) {
    ScenePrimitive s;  // a unit cylinder along z of G, centred at p_W
    s.kind = Shape::Kind::kCylinder;
    s.size = Eigen::Vector3d(0.005 * robot_size, 0.005 * robot_size, length);
    s.X_WG.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), e_W).toRotationMatrix();
    s.X_WG.translation() = p_W;
    s.color = color;
    scene->primitives.push_back(s);
  };
  const double length = 0.25 * robot_size;
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    for (int axis = 0; axis < 3; ++axis) {
      // data's poses are in the base frame R (the model's world), drawn in W.
      const Eigen::Vector3d e_W = X_WR.linear() * data.R_WB[b].col(axis);
      if (show_frames) {
        const Eigen::Vector3f color(axis == 0 ? 0.9f : 0.1f, axis == 1 ? 0.75f : 0.1f, axis == 2 ? 0.9f : 0.1f);
        stick(X_WR * data.p_WBo_W[b] + 0.5 * length * e_W, e_W, length, color);
      }
      if (show_com) stick(X_WR * data.p_WBcm_W[b], e_W, length, Eigen::Vector3f(0.08f, 0.08f, 0.08f));
    }
  }
}

void GuiApp::Impl::DrawViewport() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(W * layout.left_fraction, H * layout.viewport_fraction));
  ImGui::Begin("3D view", nullptr, kPanelFlags);
  const bool has_timeline = ReplaysLog() || session.current_motion();
  SyncScene();
  if (fitted_motion_version != session.motion_version() || fitted_source != ShownSource()) FitView();

  // The image fills the window above the timeline row.
  const float timeline_height = ImGui::GetFrameHeightWithSpacing() + 4.0f;
  ImVec2 size = ImGui::GetContentRegionAvail();
  size.y -= timeline_height;
  const int w = std::max(16, static_cast<int>(size.x)), h = std::max(16, static_cast<int>(size.y));
  // While the motion plays the view is drawn at half resolution (a quarter of
  // the pixels, which llvmpipe pays for per frame), sharp again when it stops.
  const int scale = playing ? 2 : 1;
  const int draw_w = std::max(16, w / scale), draw_h = std::max(16, h / scale);
  Camera camera = FitCamera(motion_points_W, static_cast<double>(w) / h, view);
  camera.p_WEye_W = camera.p_WTarget_W + zoom * (camera.p_WEye_W - camera.p_WTarget_W) + pan_W;
  camera.p_WTarget_W += pan_W;
  const Eigen::VectorXd q = CurrentQ();
  const int overlays = (show_com ? 1 : 0) | (show_frames ? 2 : 0);
  if (!drawn_once || draw_w != drawn_w || draw_h != drawn_h || overlays != drawn_overlays || q != drawn_q ||
      camera.p_WEye_W != drawn_eye_W || camera.p_WTarget_W != drawn_target_W) {
    const RobotModel& model = session.model();
    RobotData data(model);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
    ComputeKinematics(model, q, zero, zero, &data);
    Scene scene = BuildRobotScene(model, data, session.design.design.base_pose.X_WR());
    AddCellObstacles(cell, &scene);
    AddOverlays(model, data, &scene);
    renderer.Draw(scene, floor, camera, draw_w, draw_h);
    drawn_q = q, drawn_w = draw_w, drawn_h = draw_h, drawn_overlays = overlays, drawn_once = true;
    drawn_eye_W = camera.p_WEye_W, drawn_target_W = camera.p_WTarget_W;
  }
  // GL textures run bottom to top.
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(renderer.color_texture())),
               ImVec2(static_cast<float>(w), static_cast<float>(h)), ImVec2(0, 1), ImVec2(1, 0));
  widgets.Record("viewport");
  if (ImGui::IsItemHovered()) {
    // Left drag orbits, right drag pans, the wheel zooms.
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
      view.azimuth -= 0.01 * io.MouseDelta.x;
      view.elevation = std::clamp(view.elevation + 0.01 * io.MouseDelta.y, -1.4, 1.4);
    }
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
      const Eigen::Vector3d forward = (camera.p_WTarget_W - camera.p_WEye_W).normalized();
      const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
      const Eigen::Vector3d up = right.cross(forward);
      const double metres_per_px = (camera.p_WTarget_W - camera.p_WEye_W).norm() * std::tan(camera.fov_y / 2) * 2 / h;
      pan_W += metres_per_px * (-io.MouseDelta.x * right + io.MouseDelta.y * up);
    }
    if (io.MouseWheel != 0.0f) zoom = std::clamp(zoom * std::pow(0.9, io.MouseWheel), 0.1, 10.0);
  }
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    view = CameraView{}, zoom = 1.0, pan_W.setZero();
  }

  // Timeline: play/pause, speed, scrubber.
  if (widgets.Button("timeline.play", playing ? "Pause" : "Play", has_timeline)) playing = !playing;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::DragScalar("##speed", ImGuiDataType_Double, &speed, 0.01f, nullptr, nullptr, "x%.2f");
  speed = std::clamp(speed, 0.05, 10.0);
  ImGui::SameLine();
  widgets.Checkbox("view.com", "CoM", &show_com);
  ImGui::SameLine();
  widgets.Checkbox("view.frames", "frames", &show_frames);
  ImGui::SameLine();
  const double start = TimelineStart(), end = has_timeline ? TimelineEnd() : 0.0;
  ImGui::SetNextItemWidth(-1);
  char overlay[256];
  std::snprintf(overlay, sizeof overlay, "t = %.2f / %.2f s (%s)", t, end, ShownSource().c_str());
  ImGui::SliderScalar("##time", ImGuiDataType_Double, &t, &start, &end, overlay);
  widgets.Record("timeline.time", [this](const std::string& text, std::string* why) {
    return internal::ParseDouble(text, &t, why);
  });
  ImGui::End();
}

}  // namespace idbench::gui
