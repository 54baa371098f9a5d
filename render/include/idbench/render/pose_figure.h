// The paper's Figure 2: the robot at successive instants of a motion, one
// panel per instant, labelled "(a) 0 s", "(b) 0.3 s", …, all panels seen by
// one camera fitted to every pose (so that motion reads as motion).
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/cell.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/render/camera.h"
#include "idbench/render/image.h"
#include "idbench/render/scene_renderer.h"

namespace idbench {

struct PoseFigureOptions {
  std::vector<double> times{0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.0};  // [s], the paper's Figure 2
  std::string layout = "grid";  // "grid": rows of up to kGridColumns panels; "strip": one row
  int panel_width = 480;        // [px]
  int panel_height = 360;       // [px]
  CameraView view;
  // Where the robot stands and what stands around it: the base frame placed
  // in W (a robot the trajectory moves in its own frame R, drawn at X_WR)
  // and the cell's obstacles drawn at their poses in W.
  BasePose base_pose;
  Cell scene;

  static constexpr int kGridColumns = 4;
  static constexpr int kMaxPanels = 26;            // labels (a) … (z)
  static constexpr int kMinPanelSize = 32;         // [px] per side
  static constexpr int kMaxPanelSize = 4096;       // [px] per side
  static constexpr long long kMaxPixels = 1 << 26; // whole figure (64 Mpx, 192 MB of RGB)

  int columns() const;
  int rows() const;

  // Checks the layout, the sizes and that every time lies in [0, duration];
  // *why names the bad field (layout, times, panel_width, panel_height).
  bool IsValid(double duration, std::string* why) const;
};

// "(a) 0 s", "(b) 0.3 s", … for panel k at time t [s].
std::string PanelLabel(int k, double t);

// The figure: columns()·panel_width × rows()·panel_height pixels, panel k at
// column k % columns(), row k / columns(). Options must be valid for the
// trajectory. The camera is fitted to the robot's poses and to the parts of
// the obstacles near them (an obstacle's bounding box clipped to the robot's
// widened by half its size on every side), so that a wall or a table does not
// shrink the robot to a speck. Deterministic for a given machine.
Image RenderPoseFigure(SceneRenderer& renderer, const RobotModel& model, const Trajectory& trajectory,
                       const PoseFigureOptions& options);

}  // namespace idbench
