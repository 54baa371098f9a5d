// `idbench render`: the robot at chosen instants of a motion as one labelled
// PNG (headless); its flags fill RenderOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {
namespace {

// Fields of RenderOptions and PoseFigureOptions named in messages (the
// combined size first: one flag gives both).
constexpr FieldFlag kRenderSpellings[] = {{"panel_width x panel_height", "--size"},
                                          {"panel_width", "--size"},
                                          {"panel_height", "--size"},
                                          {"paper_accel_deg_s2", "--accel"},
                                          {"size", "--size"},
                                          {"times", "--times"},
                                          {"layout", "--layout"},
                                          {"out", "--out"},
                                          {"base_pose", "--base-pose"}};

int RenderCommand(const RenderOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = MountRobot(LoadRobotOrThrow(options.robot, load), options.base_pose);
  const std::unique_ptr<Trajectory> trajectory = MakeRenderTrajectory(model, options);
  const PoseFigureOptions figure = MakeRenderFigure(options, trajectory->duration());
  if (!figure.IsValid(trajectory->duration(), &why)) return context.UsageError(why);
  const std::string png = RenderPoseFigurePng(model, *trajectory, figure);
  const std::filesystem::path path(options.out);
  if (path.has_parent_path()) EnsureOutputDirectory(path.parent_path());
  WriteFileAtomically(path, png);
  std::printf("rendered %s along '%s' at %zu instants (%dx%d px); wrote %s\n", model.name().c_str(),
              options.trajectory.c_str(), figure.times.size(), figure.columns() * figure.panel_width,
              figure.rows() * figure.panel_height, path.c_str());
  return 0;
}

}  // namespace

CliCommand AddRenderCommand(CLI::App* app, CliContext* context) {
  auto options = std::make_shared<RenderOptions>();
  RenderOptions& render = *options;
  CLI::App* command =
      app->add_subcommand("render", "Render the robot at chosen instants of a motion as one labelled PNG (headless)");
  AddRobotFlags(command, &render.robot, context->robot_load());
  command->add_option("--trajectory", render.trajectory,
                      "Built-in motion (paper, general, general-reversed) or trajectory file (.json, .csv)")
      ->capture_default_str();
  command->add_option("--accel", render.paper_accel_deg_s2, "Acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  command->add_option("--duration", render.duration, "Length of the built-in motion [s]")->capture_default_str();
  command->add_option("--times", render.times,
                      "Instants t1,t2,... [s], one panel each (default: 8 spread over the whole motion)")
      ->delimiter(',');
  command->add_option("--layout", render.layout, "grid (rows of 4) or strip (one row)")->capture_default_str();
  command->add_option("--size", render.size, "One panel, WxH [px]")->capture_default_str();
  AddSceneFlag(command, &render.scene)->description("The cell: JSON {\"floor\": true, \"obstacles\": [boxes, cylinders, "
                                                     "spheres, meshes with world poses]}, drawn around the robot");
  AddBasePoseFlag(command, &render.base_pose);
  AddOutFlag(command, &render.out, "PNG file to write")->capture_default_str();
  context->AddSpellings(kRenderSpellings);
  return {command, [options, context] { return RenderCommand(*options, *context->robot_load(), *context); }};
}

}  // namespace idbench::cli
