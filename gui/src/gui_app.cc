#include "idbench/gui/gui_app.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_library.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/render/camera.h"
#include "idbench/render/robot_scene.h"
#include "idbench/render/scene_renderer.h"
#include "widgets.h"

namespace idbench::gui {
namespace {

using internal::Widgets;

constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                         ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
const ImVec4 kErrorColor(0.80f, 0.10f, 0.10f, 1.0f);
const ImVec4 kDimColor(0.45f, 0.45f, 0.45f, 1.0f);

// "1.23e+04", "inf" (limits), "-" (NaN).
std::string Number(double v, const char* format = "%.4g") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void TextCell(const std::string& text, const ImVec4* color = nullptr) {
  if (color) ImGui::TextColored(*color, "%s", text.c_str());
  else ImGui::TextUnformatted(text.c_str());
}

std::vector<std::string> MotionNames(bool with_designed) {
  std::vector<std::string> names;
  if (with_designed) names.push_back("designed");
  for (const std::string& n : BuiltinMotionNames()) names.push_back(n);
  return names;
}

}  // namespace

struct GuiApp::Impl {
  Impl(const SessionOptions& options, GlProcLoader loader) : session(options), renderer(loader), widgets(&registry) {}

  Session session;
  SceneRenderer renderer;
  WidgetRegistry registry;
  Widgets widgets;
  GuiLayout layout;

  // Robot panel
  std::string robot_choice;   // the built-in picked in the combo
  std::string urdf_path;
  std::optional<std::string> pending_robot;  // to load at the end of the frame

  // Viewport and timeline
  double t = 0.0;             // [s]
  bool playing = false;
  double speed = 1.0;
  CameraView view;
  double zoom = 1.0;          // eye distance scale
  Eigen::Vector3d pan_W = Eigen::Vector3d::Zero();  // [m]
  bool show_com = false;      // centres of mass
  bool show_frames = false;   // link frames (x red, y green, z blue), at the hinge points
  double robot_size = 1.0;    // [m] diagonal of the robot's extent over the motion (marker sizes)
  int fitted_motion_version = -1;
  std::vector<Eigen::Vector3d> motion_points_W;  // the robot's extent over the motion
  Floor floor;
  std::string shown_motion_key;
  // What the texture shows (redrawn only when it changes).
  Eigen::VectorXd drawn_q;
  Eigen::Vector3d drawn_eye_W = Eigen::Vector3d::Zero(), drawn_target_W = Eigen::Vector3d::Zero();
  int drawn_w = 0, drawn_h = 0;
  int drawn_overlays = 0;
  bool drawn_once = false;

  std::optional<std::string> screenshot_request;
  size_t shown_messages = 0;  // the messages panel scrolls to a new one

  Eigen::VectorXd CurrentQ() const {
    const Trajectory* motion = session.current_motion();
    if (!motion) return Eigen::VectorXd::Zero(session.model().n_dof());
    return motion->At(std::clamp(t, 0.0, motion->duration())).q;
  }

  // A button that starts a job, with what the job is doing beside it while it runs.
  bool JobButton(const std::string& name, const char* label, bool enabled, bool running, const char* doing) {
    const bool pressed = widgets.Button(name, label, enabled);
    if (running) {
      ImGui::SameLine();
      ImGui::TextUnformatted(doing);
    }
    return pressed;
  }

  void SyncMotion();
  void FitView();
  void AddOverlays(const RobotModel& model, const RobotData& data, Scene* scene) const;
  void DrawViewport();
  void DrawRobotPanel();
  void DrawDesignTab();
  void DrawExperimentTab();
  void DrawPerBodyExperiment(bool busy);
  void DrawCompareTab();
  void DrawExportTab();
  void DrawMessages();
};

// ---- Viewport ---------------------------------------------------------------

// Rebuilds the built-in motion when its name or duration was edited (by a
// widget or a script), and keeps the timeline inside the motion.
void GuiApp::Impl::SyncMotion() {
  const std::string key = session.motion + "/" + std::to_string(session.builtin_duration);
  if (key != shown_motion_key) {
    if (session.motion != "designed" || session.design_report()) session.SelectMotion(session.motion);
    shown_motion_key = key;
  }
  if (const Trajectory* motion = session.current_motion()) t = std::clamp(t, 0.0, motion->duration());
}

// The robot's extent over the whole motion, so that the camera does not jump
// while it plays.
void GuiApp::Impl::FitView() {
  const RobotModel& model = session.model();
  const Trajectory* motion = session.current_motion();
  RobotData data(model);
  motion_points_W.clear();
  const int n_poses = motion ? 9 : 1;
  for (int k = 0; k < n_poses; ++k) {
    const Eigen::VectorXd q = motion ? motion->At(motion->duration() * k / (n_poses - 1)).q
                                     : Eigen::VectorXd::Zero(model.n_dof());
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
    ComputeKinematics(model, q, zero, zero, &data);
    const std::vector<Eigen::Vector3d> points = BuildRobotScene(model, data).BoundingPoints();
    motion_points_W.insert(motion_points_W.end(), points.begin(), points.end());
  }
  floor = FitFloor(motion_points_W);
  Eigen::Vector3d lo = motion_points_W.front(), hi = lo;
  for (const Eigen::Vector3d& p : motion_points_W) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  robot_size = std::max((hi - lo).norm(), 1e-3);
  fitted_motion_version = session.motion_version();
}

// Markers on demand, sized by the robot and long enough to stick out of the
// (solid) links: every link frame's axes from its hinge point (x red, y green,
// z blue), and a dark cross of three sticks through every centre of mass.
void GuiApp::Impl::AddOverlays(const RobotModel& model, const RobotData& data, Scene* scene) const {
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
      const Eigen::Vector3d e_W = data.R_WB[b].col(axis);
      if (show_frames) {
        const Eigen::Vector3f color(axis == 0 ? 0.9f : 0.1f, axis == 1 ? 0.75f : 0.1f, axis == 2 ? 0.9f : 0.1f);
        stick(data.p_WBo_W[b] + 0.5 * length * e_W, e_W, length, color);
      }
      if (show_com) stick(data.p_WBcm_W[b], e_W, length, Eigen::Vector3f(0.08f, 0.08f, 0.08f));
    }
  }
}

void GuiApp::Impl::DrawViewport() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(W * layout.left_fraction, H * layout.viewport_fraction));
  ImGui::Begin("3D view", nullptr, kPanelFlags);
  const Trajectory* motion = session.current_motion();
  if (fitted_motion_version != session.motion_version()) FitView();

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
    Scene scene = BuildRobotScene(model, data);
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
  if (widgets.Button("timeline.play", playing ? "Pause" : "Play", motion != nullptr)) playing = !playing;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::DragScalar("##speed", ImGuiDataType_Double, &speed, 0.01f, nullptr, nullptr, "x%.2f");
  speed = std::clamp(speed, 0.05, 10.0);
  ImGui::SameLine();
  widgets.Checkbox("view.com", "CoM", &show_com);
  ImGui::SameLine();
  widgets.Checkbox("view.frames", "frames", &show_frames);
  ImGui::SameLine();
  const double duration = motion ? motion->duration() : 0.0;
  ImGui::SetNextItemWidth(-1);
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "t = %.2f / %.2f s (%s)", t, duration, session.motion.c_str());
  const double start = 0.0;
  ImGui::SliderScalar("##time", ImGuiDataType_Double, &t, &start, &duration, overlay);
  widgets.Record("timeline.time", [this](const std::string& text, std::string* why) {
    return internal::ParseDouble(text, &t, why);
  });
  ImGui::End();
}

// ---- Robot panel ----------------------------------------------------------

void GuiApp::Impl::DrawRobotPanel() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  ImGui::SetNextWindowPos(ImVec2(0, H * layout.viewport_fraction));
  ImGui::SetNextWindowSize(ImVec2(W * layout.left_fraction, H * (1.0f - layout.viewport_fraction)));
  ImGui::Begin("Robot", nullptr, kPanelFlags);
  const RobotModel& model = session.model();
  const bool idle = !session.any_running();

  ImGui::SetNextItemWidth(120);
  widgets.Combo("robot.builtin", "##builtin", &robot_choice, BuiltinRobotNames());
  ImGui::SameLine();
  // Loading replaces the model this frame draws from: done after the panels.
  if (widgets.Button("robot.load_builtin", "Load", idle)) pending_robot = robot_choice;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(std::max(120.0f, ImGui::GetContentRegionAvail().x - 110));
  widgets.InputText("robot.urdf", "##urdf", &urdf_path);
  ImGui::SameLine();
  if (widgets.Button("robot.load_urdf", "Open URDF", idle && !urdf_path.empty())) pending_robot = urdf_path;
  ImGui::Text("%s: %d joints, source '%s'", model.name().c_str(), model.n_dof(), session.robot_source().c_str());

  // Joint table: the current q and the design's limits (editable).
  const Eigen::VectorXd q = CurrentQ();
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingStretchSame;
  const float table_height = ImGui::GetContentRegionAvail().y - ImGui::GetFrameHeightWithSpacing() - 4;
  if (ImGui::BeginTable("joints", 7, flags, ImVec2(0, table_height))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("joint", ImGuiTableColumnFlags_WidthFixed, 50.0f);
    ImGui::TableSetupColumn("q [rad]", ImGuiTableColumnFlags_WidthFixed, 60.0f);
    for (const char* c : {"q min [rad]", "q max [rad]", "qd max [rad/s]", "qdd max [rad/s²]", "τ max [N m]"})
      ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (int j = 0; j < model.n_dof() && j < static_cast<int>(session.limits.size()); ++j) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted(model.link(j).joint_name.empty() ? model.link(j).name.c_str()
                                                               : model.link(j).joint_name.c_str());
      ImGui::TableSetColumnIndex(1);
      ImGui::AlignTextToFramePadding();
      ImGui::Text("%.3f", q[j]);
      JointLimits& l = session.limits[static_cast<size_t>(j)];
      double* cells[] = {&l.q_min, &l.q_max, &l.qd_max, &l.qdd_max, &l.tau_max};
      const char* keys[] = {"q_min", "q_max", "qd_max", "qdd_max", "tau_max"};
      for (int c = 0; c < 5; ++c) {
        ImGui::TableSetColumnIndex(2 + c);
        ImGui::SetNextItemWidth(-FLT_MIN);
        widgets.InputDouble("limits." + std::to_string(j + 1) + "." + keys[c], "", cells[c], "%.4g");
      }
    }
    ImGui::EndTable();
  }
  if (widgets.Button("limits.fill", "Fill missing limits")) session.FillMissingLimits();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("q within [%g, %g] rad, qd %g rad/s, qdd %g rad/s²", session.fill_limits.q_min,
                      session.fill_limits.q_max, session.fill_limits.qd_max, session.fill_limits.qdd_max);
  ImGui::SameLine();
  if (widgets.Button("limits.reset", "Robot file's limits")) session.ResetLimits();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "inf = no limit; the design needs finite q, qd, qdd limits");
  ImGui::End();
}

// ---- Design tab -------------------------------------------------------------

void GuiApp::Impl::DrawDesignTab() {
  DesignCommandOptions& d = session.design;
  const bool running = session.running(JobKind::kDesign);
  ImGui::BeginDisabled(running);
  ImGui::PushItemWidth(110);
  ImGui::TextColored(kDimColor, "Fourier series, one period of 1/f0");
  widgets.InputInt("design.harmonics", "harmonics", &d.design.harmonics, 1, 20);
  ImGui::SameLine(260);
  widgets.InputDouble("design.f0", "f0 [Hz]", &d.design.f0);
  widgets.InputInt("design.samples", "samples", &d.design.samples, 4, 100000);
  ImGui::SameLine(260);
  widgets.InputDouble("design.margin", "margin", &d.design.margin);
  widgets.Checkbox("design.rest_to_rest", "rest to rest", &d.design.rest_to_rest);
  widgets.Combo("design.model", "model", &d.model, {"torque", "per-body"});
  ImGui::SameLine(260);
  std::vector<std::string> criteria{""};
  for (const std::string& c : DesignCriterionNames()) criteria.push_back(c);
  widgets.Combo("design.criterion", "criterion", &d.criterion, criteria);
  widgets.Combo("design.algorithm", "algorithm", &d.algorithm, DesignAlgorithmNames());
  ImGui::SameLine(260);
  widgets.InputInt("design.starts", "starts", &d.design.starts, 1, 64);
  widgets.InputUnsigned("design.seed", "seed", &d.design.seed);
  ImGui::SameLine(260);
  widgets.InputInt("design.max_evaluations", "evaluations", &d.design.max_evaluations, 1, 1000000);
  widgets.InputInt("design.threads", "threads", &d.design.threads, 1, 64);
  ImGui::SameLine(260);
  widgets.InputDouble("design.clearance", "clearance [m]", &d.design.clearance);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();

  if (widgets.Button("design.run", "Run design", !running)) session.StartDesign();
  ImGui::SameLine();
  if (widgets.Button("design.stop", "Stop", running)) session.StopDesign();
  const std::vector<double> curve = session.DesignCurve();
  if (running) {
    ImGui::SameLine();
    ImGui::Text("running: %zu progress reports%s", curve.size(), curve.empty() ? ", nothing feasible yet" : "");
  }

  // Live curve of the best criterion over all starts.
  std::vector<float> values(curve.begin(), curve.end());
  if (values.size() == 1) values.push_back(values.front());  // a line needs two points
  std::string overlay = curve.empty() ? "best criterion (none yet)" : "best criterion " + Number(curve.back());
  ImGui::PlotLines("##curve", values.empty() ? nullptr : values.data(), static_cast<int>(values.size()), 0,
                   overlay.c_str(), FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 90));
  widgets.Record("design.curve");

  const auto& report = session.design_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "No design yet.");
    return;
  }
  const DesignResult& r = report->result;
  if (ImGui::BeginTable("design_result", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchSame)) {
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("initial");
    ImGui::TableSetupColumn("designed");
    ImGui::TableHeadersRow();
    auto row = [](const char* name, double a, double b) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(name);
      ImGui::TableSetColumnIndex(1);
      TextCell(Number(a));
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(b));
    };
    row("criterion", r.initial_value, r.value);
    row("cond(W)", r.initial.cond, r.final.cond);
    row("normalised cond", r.initial.cond_normalised, r.final.cond_normalised);
    row("log det(WᵀW/m)", r.initial.log_det, r.final.log_det);
    row("σ_min(W)", r.initial.sigma_min, r.final.sigma_min);
    ImGui::EndTable();
  }
  ImGui::Text("%d evaluations in %.2f s; %s at %g Hz%s", r.evaluations, r.wall_seconds,
              r.check.feasible() ? "feasible" : "INFEASIBLE", r.check.rate_hz, r.stopped ? " (stopped)" : "");
  if (!r.check.feasible()) ImGui::TextColored(kErrorColor, "%s", r.check.Explain().c_str());

  // Per-constraint margins, tightest first.
  std::vector<ConstraintMargin> margins = r.check.margins;
  auto relative = [](const ConstraintMargin& m) { return m.limit > 0 ? m.margin / m.limit : m.margin; };
  std::sort(margins.begin(), margins.end(),
            [&](const ConstraintMargin& a, const ConstraintMargin& b) { return relative(a) < relative(b); });
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingStretchSame;
  if (ImGui::BeginTable("margins", 6, flags, ImVec2(0, std::max(60.0f, ImGui::GetContentRegionAvail().y)))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* c : {"joint", "limit on", "t [s]", "value", "limit", "margin"}) ImGui::TableSetupColumn(c);  // clearance: the pair
    ImGui::TableHeadersRow();
    for (const ConstraintMargin& m : margins) {
      ImGui::TableNextRow();
      const ImVec4* color = m.margin < 0 ? &kErrorColor : nullptr;
      ImGui::TableSetColumnIndex(0);
      TextCell(m.quantity == "clearance" ? m.pair : std::to_string(m.joint + 1), color);
      ImGui::TableSetColumnIndex(1);
      TextCell(m.quantity, color);
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(m.time, "%.3f"), color);
      ImGui::TableSetColumnIndex(3);
      TextCell(Number(m.value), color);
      ImGui::TableSetColumnIndex(4);
      TextCell(Number(m.limit), color);
      ImGui::TableSetColumnIndex(5);
      TextCell(Number(m.margin), color);
    }
    ImGui::EndTable();
  }
}

// ---- Experiment tab ---------------------------------------------------------

void GuiApp::Impl::DrawExperimentTab() {
  SimulateOptions& s = session.simulate;
  IdentifyOptions& id = session.identify;
  const bool busy = session.running(JobKind::kSimulate) || session.running(JobKind::kIdentify) ||
                    session.running(JobKind::kPerBody);
  ImGui::PushItemWidth(110);
  ImGui::BeginDisabled(busy);
  widgets.Combo("experiment.motion", "motion", &session.motion, MotionNames(true));
  ImGui::SameLine(260);
  ImGui::BeginDisabled(session.motion == "designed");  // a designed motion is one period
  widgets.InputDouble("experiment.duration", "duration [s]", &session.builtin_duration);
  ImGui::EndDisabled();
  widgets.Combo("identify.model", "identification model", &id.model, {"torque", "per-body"});
  ImGui::EndDisabled();
  if (id.model == "per-body") {
    ImGui::PopItemWidth();
    DrawPerBodyExperiment(busy);
    return;
  }
  ImGui::BeginDisabled(busy);
  if (s.sensors.tau_noise.empty()) s.sensors.tau_noise.push_back(0.0);
  widgets.InputDouble("experiment.tau_noise", "τ noise σ [N m]", &s.sensors.tau_noise[0]);
  ImGui::SameLine(260);
  widgets.InputDouble("experiment.q_noise", "q noise σ [rad]", &s.sensors.q_noise);
  widgets.InputUnsigned("experiment.seed", "noise seed", &s.sensors.seed);
  ImGui::SameLine(260);
  widgets.InputDouble("experiment.rate", "rate [Hz]", &s.sensors.rate_hz);
  ImGui::EndDisabled();
  if (widgets.Button("experiment.simulate", "Simulate", !busy)) session.StartSimulate();
  ImGui::SameLine();
  if (session.log()) ImGui::Text("log: %d samples", session.log()->n_samples());
  else if (session.running(JobKind::kSimulate)) ImGui::Text("simulating...");
  else ImGui::TextColored(kDimColor, "no log yet");

  ImGui::BeginDisabled(busy);
  widgets.Combo("identify.estimator", "estimator", &id.estimator, {"ols", "wls", "pc"});
  ImGui::EndDisabled();
  ImGui::PopItemWidth();
  ImGui::SameLine();
  if (JobButton("experiment.identify", "Identify", !busy && session.log().has_value(),
                session.running(JobKind::kIdentify), "identifying..."))
    session.StartIdentify();

  const auto& report = session.identify_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "Nothing identified yet (joint-torque model, base parameters).");
    return;
  }
  const std::vector<IdentifiedRow> rows = session.IdentifiedRows();
  const JointTorqueIdentification& ident = report->identification;
  ImGui::Text("%d base parameters, cond(W) %.4g, torque error %.3g%% (robot file %.3g%%)", ident.base.n_base(),
              ident.linear.cond, 100 * ident.fit.relative_error, 100 * ident.model_fit.relative_error);
  if (ident.linear.rank < ident.base.n_base()) {
    ImGui::TextColored(kErrorColor, "This log determines only %d combinations (rank): the motion does not excite the "
                       "rows marked n/a.", ident.linear.rank);
  }
  // Bars: |relative error| per base parameter [%].
  std::vector<float> bars;
  for (const IdentifiedRow& row : rows) bars.push_back(std::isnan(row.relative_error) ? 0.0f : static_cast<float>(100 * std::abs(row.relative_error)));
  ImGui::PlotHistogram("##bars", bars.data(), static_cast<int>(bars.size()), 0, "|error| per base parameter [%]", 0.0f,
                       FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("experiment.bars");

  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_Resizable;
  const std::vector<std::string> unexcited = session.UnexcitedParameters();
  const float reserve = unexcited.empty() ? 0.0f : 2.5f * ImGui::GetTextLineHeightWithSpacing();
  if (ImGui::BeginTable("identified", 6, flags, ImVec2(0, ImGui::GetContentRegionAvail().y - reserve))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("base parameter", ImGuiTableColumnFlags_WidthStretch);
    for (const char* c : {"true", "identified", "error %", "%σ", "flag"}) ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthFixed, 0.0f);
    ImGui::TableHeadersRow();
    for (const IdentifiedRow& row : rows) {
      ImGui::TableNextRow();
      const bool missing = row.status == ParameterStatus::kNotIdentifiable;
      const ImVec4* color = row.status == ParameterStatus::kPoor || missing             ? &kErrorColor
                            : row.status == ParameterStatus::kIndistinguishableFromZero ? &kDimColor
                                                                                         : nullptr;
      ImGui::TableSetColumnIndex(0);
      TextCell(row.name, color);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.name.c_str());
      ImGui::TableSetColumnIndex(1);
      TextCell(Number(row.model_value, "%.5g"), color);
      ImGui::TableSetColumnIndex(2);
      TextCell(Number(row.identified, "%.5g"), color);
      ImGui::TableSetColumnIndex(3);
      TextCell(Number(100 * row.relative_error, "%.2g"), color);
      ImGui::TableSetColumnIndex(4);
      TextCell(Number(row.sigma_percent, "%.2g"), color);
      ImGui::TableSetColumnIndex(5);
      const bool zero = row.status == ParameterStatus::kIndistinguishableFromZero;
      TextCell(row.status == ParameterStatus::kDetermined ? "ok" : zero ? "~0" : missing ? "n/a" : "poor", color);
      if (missing && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Not identifiable: this log does not excite it (W is rank deficient); no value is given");
      }
      if (zero && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("|identified| <= %g σ: the data cannot tell it from zero (a parameter that is 0, or one "
                          "this motion hardly excites)", kZeroSigmas);
      } else if (row.status == ParameterStatus::kPoor && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%%σ above %g %%: poorly identified by this motion", kDeterminedSigmaPercent);
      }
    }
    ImGui::EndTable();
  }
  if (!unexcited.empty()) {
    std::string text = "Not identifiable (no effect on any torque):";
    for (const std::string& n : unexcited) text += " " + n;
    ImGui::TextWrapped("%s", text.c_str());
  }
}

// The per-body experiment (`idbench run`): Bullet's hinge wrenches along the
// motion, every body's mass and principal inertias, or why not.
void GuiApp::Impl::DrawPerBodyExperiment(bool busy) {
  RunOptions& run = session.per_body;
  ImGui::BeginDisabled(busy);
  widgets.Checkbox("per_body.all_samples", "every step (else the paper's 5 instants)", &run.all_samples);
  ImGui::EndDisabled();
  if (JobButton("experiment.per_body", "Run per-body experiment", !busy, session.running(JobKind::kPerBody),
                "simulating and identifying..."))
    session.StartPerBody();
  const auto& result = session.per_body_result();
  if (!result) {
    ImGui::TextColored(kDimColor, "No per-body identification yet (hinge wrenches, no sensor noise).");
    return;
  }
  ImGui::Text("%d samples; largest relative error %.3g (%s)", result->n_samples, result->max_rel_error,
              result->max_rel_error_at.c_str());
  std::vector<float> bars;
  for (const BodyResult& body : result->bodies)
    for (const ParameterResult& p : body.parameters)
      bars.push_back(p.identifiable ? static_cast<float>(std::log10(std::max(p.rel_error, 1e-16)) + 16) : 0.0f);
  ImGui::PlotHistogram("##per_body_bars", bars.data(), static_cast<int>(bars.size()), 0,
                       "16 + log10 relative error per parameter (0: not identifiable)", 0.0f, FLT_MAX,
                       ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("experiment.per_body_bars");
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY;
  if (ImGui::BeginTable("per_body", 5, flags, ImVec2(0, ImGui::GetContentRegionAvail().y))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* c : {"parameter", "true", "identified", "rel. error"})
      ImGui::TableSetupColumn(c, ImGuiTableColumnFlags_WidthFixed, 85.0f);
    ImGui::TableSetupColumn("status", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (const BodyResult& body : result->bodies) {
      for (const ParameterResult& p : body.parameters) {
        ImGui::TableNextRow();
        const ImVec4* color = p.identifiable ? nullptr : &kErrorColor;
        ImGui::TableSetColumnIndex(0);
        TextCell(body.name + "." + p.name, color);
        ImGui::TableSetColumnIndex(1);
        TextCell(Number(p.true_value, "%.6g"), color);
        ImGui::TableSetColumnIndex(2);
        TextCell(Number(p.identified, "%.6g"), color);
        ImGui::TableSetColumnIndex(3);
        TextCell(Number(p.rel_error, "%.2g"), color);
        ImGui::TableSetColumnIndex(4);
        TextCell(p.identifiable ? "ok" : "NOT IDENTIFIABLE", color);
        if (!p.identifiable && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.reason.c_str());
      }
    }
    ImGui::EndTable();
  }
}

// ---- Compare tab --------------------------------------------------------------

void GuiApp::Impl::DrawCompareTab() {
  CompareOptions& c = session.compare;
  const bool running = session.running(JobKind::kCompare);
  ImGui::BeginDisabled(running);
  ImGui::TextUnformatted(session.design_report() ? "Motions: the designed one, and" : "Motions (no design yet):");
  for (const std::string& name : BuiltinMotionNames()) {
    ImGui::SameLine();
    bool on = std::find(session.compare_builtins.begin(), session.compare_builtins.end(), name) !=
              session.compare_builtins.end();
    if (widgets.Checkbox("compare." + name, name.c_str(), &on)) {
      auto& list = session.compare_builtins;
      list.erase(std::remove(list.begin(), list.end(), name), list.end());
      if (on) list.push_back(name);
    }
  }
  ImGui::PushItemWidth(110);
  widgets.InputInt("compare.samples", "samples", &c.samples, 4, 100000);
  ImGui::SameLine(260);
  widgets.InputInt("compare.trials", "trials", &c.trials, 2, 100000);
  if (c.tau_noise.empty()) c.tau_noise.push_back(0.05);
  widgets.InputDouble("compare.tau_noise", "τ noise σ [N m]", &c.tau_noise[0]);
  ImGui::SameLine(260);
  widgets.InputUnsigned("compare.seed", "seed", &c.seed);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();
  if (JobButton("compare.run", "Compare", !running, running, "comparing (Bullet + Monte Carlo)..."))
    session.StartCompare();

  const auto& report = session.compare_report();
  if (!report) {
    ImGui::TextColored(kDimColor, "No comparison yet.");
    return;
  }
  std::vector<float> bars;
  for (const MotionComparison& m : report->motions)
    bars.push_back(std::isfinite(m.designed.cond) ? static_cast<float>(std::log10(m.designed.cond)) : 0.0f);
  ImGui::PlotHistogram("##compare_bars", bars.data(), static_cast<int>(bars.size()), 0,
                       "log10 cond(W) per motion (0: rank deficient)", 0.0f, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 70));
  widgets.Record("compare.bars");
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("compare", 8, flags)) {
    for (const char* h : {"motion", "cond", "norm. cond", "log det", "σ_min", "Bullet cond", "mean err", "limits"})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const MotionComparison& m : report->motions) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      const std::string name = m.name == session.OutPath("trajectory.json") ? "designed"
                               : m.name.size() > 24                       ? "..." + m.name.substr(m.name.size() - 21)
                                                                          : m.name;
      TextCell(name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m.name.c_str());
      const double cells[] = {m.designed.cond, m.designed.cond_normalised, m.designed.log_det, m.designed.sigma_min,
                              m.realised.cond, m.mean_relative_error};
      for (int k = 0; k < 6; ++k) {
        ImGui::TableSetColumnIndex(1 + k);
        if (k == 0 && !m.unexcited.empty()) {  // cond(W) = inf: name what the motion leaves undetermined
          TextCell("rank deficient", &kErrorColor);
          if (ImGui::IsItemHovered()) {
            std::string names;
            for (const std::string& n : m.unexcited) names += (names.empty() ? "" : ", ") + n;
            ImGui::SetTooltip("This motion does not determine: %s", names.c_str());
          }
          continue;
        }
        TextCell(Number(cells[k], "%.3g"));
      }
      ImGui::TableSetColumnIndex(7);
      TextCell(m.limits.feasible() ? "ok" : "violated", m.limits.feasible() ? nullptr : &kErrorColor);
      if (!m.limits.feasible() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", m.limits.Explain().c_str());
    }
    ImGui::EndTable();
  }
}

// ---- Export tab -------------------------------------------------------------

void GuiApp::Impl::DrawExportTab() {
  ImGui::SetNextItemWidth(-90);
  widgets.InputText("export.dir", "output dir", &session.out_dir);
  if (widgets.Button("export.trajectory_json", "Trajectory JSON", session.design_report().has_value()))
    session.ExportTrajectoryJson();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "the designed motion's coefficients: trajectory.json");
  if (widgets.Button("export.trajectory_csv", "Trajectory CSV", session.current_motion() != nullptr))
    session.ExportTrajectoryCsv();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "the shown motion at %g Hz: trajectory.csv", session.design.csv_rate_hz);
  if (widgets.Button("export.urdf", "Identified URDF", session.identify_report().has_value()))
    session.ExportIdentifiedUrdf();
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "physically consistent parameters: identified.urdf");
  if (JobButton("export.report", "Report", session.identify_report().has_value() && !session.running(JobKind::kReport),
                session.running(JobKind::kReport), "writing the report..."))
    session.StartReport();
  else if (!session.running(JobKind::kReport)) {
    ImGui::SameLine();
    ImGui::TextColored(kDimColor, "the identification's report.html, report.pdf and plots");
  }
  if (widgets.Button("export.screenshot", "Screenshot")) screenshot_request = session.OutPath("screenshot.png");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "this window: screenshot.png");
}

// ---- Messages ---------------------------------------------------------------

void GuiApp::Impl::DrawMessages() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  const float x = W * layout.left_fraction;
  ImGui::SetNextWindowPos(ImVec2(x, H - layout.messages_height));
  ImGui::SetNextWindowSize(ImVec2(W - x, layout.messages_height));
  ImGui::Begin("Messages", nullptr, kPanelFlags);
  const auto& messages = session.messages();
  for (const SessionMessage& m : messages) {
    const bool error = m.level == SessionMessage::Level::kError;
    if (error) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", m.text.c_str());
    if (error) ImGui::PopStyleColor();
  }
  if (messages.size() != shown_messages) ImGui::SetScrollHereY(1.0f);
  shown_messages = messages.size();
  ImGui::End();
}

// ---- Frame ------------------------------------------------------------------

GuiApp::GuiApp(const SessionOptions& options, GlProcLoader loader) : impl_(std::make_unique<Impl>(options, loader)) {
  // The combo starts at the robot the session opened (when it is a built-in).
  const std::vector<std::string> names = BuiltinRobotNames();
  const std::string& source = impl_->session.robot_source();
  impl_->robot_choice = std::find(names.begin(), names.end(), source) != names.end() ? source : names.front();
}

GuiApp::~GuiApp() = default;

void GuiApp::Frame(double dt_seconds) {
  Impl& m = *impl_;
  m.registry.BeginFrame();
  m.session.Poll();
  m.SyncMotion();
  if (m.playing) {
    if (const Trajectory* motion = m.session.current_motion()) {
      m.t += dt_seconds * m.speed;
      if (m.t > motion->duration()) m.t = 0.0;
    } else {
      m.playing = false;
    }
  }

  m.DrawViewport();
  m.DrawRobotPanel();

  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  const float x = W * m.layout.left_fraction;
  ImGui::SetNextWindowPos(ImVec2(x, 0));
  ImGui::SetNextWindowSize(ImVec2(W - x, H - m.layout.messages_height));
  ImGui::Begin("Workbench", nullptr, kPanelFlags);
  if (ImGui::BeginTabBar("tabs")) {
    struct Tab {
      const char* name;
      const char* label;
      void (Impl::*draw)();
    };
    for (const Tab& tab : {Tab{"tab.design", "Design", &Impl::DrawDesignTab},
                           Tab{"tab.experiment", "Experiment", &Impl::DrawExperimentTab},
                           Tab{"tab.compare", "Compare", &Impl::DrawCompareTab},
                           Tab{"tab.export", "Export", &Impl::DrawExportTab}}) {
      const bool open = ImGui::BeginTabItem(tab.label);
      m.widgets.Record(tab.name);
      if (open) {
        (m.*tab.draw)();
        ImGui::EndTabItem();
      }
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
  m.DrawMessages();
  m.registry.EndFrame();
  if (m.pending_robot) {
    if (m.session.LoadRobot(*m.pending_robot)) m.t = 0.0, m.playing = false;
    m.pending_robot.reset();
  }
}

Session& GuiApp::session() { return impl_->session; }
const WidgetRegistry& GuiApp::widgets() const { return impl_->registry; }
GuiLayout& GuiApp::layout() { return impl_->layout; }
double GuiApp::time() const { return impl_->t; }
bool GuiApp::playing() const { return impl_->playing; }

std::optional<std::string> GuiApp::TakeScreenshotRequest() {
  std::optional<std::string> request;
  request.swap(impl_->screenshot_request);
  return request;
}

}  // namespace idbench::gui
