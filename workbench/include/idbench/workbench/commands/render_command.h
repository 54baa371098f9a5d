// `idbench render`: the robot at chosen instants of a motion as one labelled
// PNG figure (the paper's Figure 2), rendered headless with OSMesa.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/render/image.h"
#include "idbench/render/pose_figure.h"
#include "idbench/workbench/commands/run_command.h"

namespace idbench {

struct RenderOptions {
  std::string robot = "paper6r";      // built-in name or URDF path
  std::string trajectory = "paper";   // built-in motion or trajectory file (trajectory_file.h)
  double paper_accel_deg_s2 = 30.0;   // acceleration of the "paper" motion [deg/s²]
  double duration = 2.0;              // of a built-in motion [s] (a file brings its own)
  std::vector<double> times;          // [s]; empty: DefaultFigureTimes over the whole motion
  std::string layout = "grid";        // grid | strip
  std::string size = "480x360";       // one panel, W x H [px]
  std::string out = "out/figure.png";
  std::string scene;                  // the cell's JSON (scene_file.h), drawn around the robot; "" none
  BasePose base_pose;                 // where the robot's base stands in the world (base_pose.h)

  // The figure options these stand for, for a motion of `duration` seconds
  // (no times given: DefaultFigureTimes(duration); a malformed size gives 0 x 0),
  // without the scene (MakeRenderFigure reads it).
  PoseFigureOptions figure(double duration) const;
  // Checks what does not need the trajectory; *why names the bad field
  // (size, duration, paper_accel_deg_s2, times, layout, out, base_pose).
  bool IsValid(std::string* why) const;
};

// Reads "WxH" (positive integers); false if malformed.
bool ParseImageSize(const std::string& text, int* width, int* height);

// The paper's Figure 2 instants 0, 0.3, …, 1.8, 2 s scaled to a motion of
// `duration` seconds: t_k = min(0.15·k·duration, duration), k = 0…7, rounded
// to 3 significant digits.
std::vector<double> DefaultFigureTimes(double duration);

// figure(duration) with the scene file read into it. Throws
// std::invalid_argument naming the file and the field of a bad scene.
PoseFigureOptions MakeRenderFigure(const RenderOptions& options, double duration);

// The motion to draw (LoadTrajectoryArg). Throws std::invalid_argument naming
// an unknown motion or a bad file.
std::unique_ptr<Trajectory> MakeRenderTrajectory(const RobotModel& model, const RenderOptions& options);

// Renders the figure headless (OSMesa, MSAA 4). The options must be valid for
// the trajectory. Throws std::runtime_error when no OpenGL 3.3 context can be
// created.
Image RenderPoseFigureImage(const RobotModel& model, const Trajectory& trajectory, const PoseFigureOptions& options);
// The same encoded as PNG.
std::string RenderPoseFigurePng(const RobotModel& model, const Trajectory& trajectory,
                                const PoseFigureOptions& options);

// figure.png of `idbench run`: the run's motion at DefaultFigureTimes.
std::string RenderRunFigurePng(const RobotModel& model, const RunOptions& options);

}  // namespace idbench
