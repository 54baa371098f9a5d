#include "common_flags.h"

#include <algorithm>
#include <cstdio>

#include "cli_command.h"

namespace idbench::cli {

CLI::Option* AddRobotFlag(CLI::App* command, std::string* robot, const std::string& help) {
  return command->add_option("--robot", *robot, help)->capture_default_str();
}

void AddRobotLoadFlags(CLI::App* command, UrdfLoadOptions* load) {
  command
      ->add_option_function<std::vector<std::string>>(
          "--lock",
          [load](const std::vector<std::string>& locks) {
            for (const std::string& lock : locks) {
              std::string why;
              if (!AddJointLock(lock, load, &why)) throw CLI::ValidationError(why);
            }
          },
          "URDF: hold a joint at a value [rad, or m if prismatic], e.g. panda_finger_joint1=0.04; joints off the "
          "chain are held at 0 by default")
      ->delimiter(',')
      ->type_name("JOINT=VALUE");
  command->add_option("--tip", load->tip_link,
                      "URDF: the arm's last link, when the file branches (default: the end of its one revolute chain)")
      ->type_name("LINK");
}

void AddRobotFlags(CLI::App* command, std::string* robot, UrdfLoadOptions* load, const std::string& help) {
  AddRobotFlag(command, robot, help);
  AddRobotLoadFlags(command, load);
}

RobotModel LoadRobotOrThrow(const std::string& name_or_path, const UrdfLoadOptions& load,
                            std::optional<Transmission>* transmission) {
  const std::vector<std::string> builtins = BuiltinRobotNames();
  if (!load.empty() && std::find(builtins.begin(), builtins.end(), name_or_path) != builtins.end()) {
    throw UsageException("--lock and --tip apply to URDF files, not to the built-in robot '" + name_or_path + "'");
  }
  UrdfLoadResult loaded = LoadRobot(name_or_path, load);
  for (const std::string& w : loaded.warnings) std::fprintf(stderr, "idbench: warning: %s\n", SharedFlagSpelling(w).c_str());
  if (transmission) *transmission = loaded.transmission;
  return std::move(loaded.model);
}

CLI::Option* AddOutFlag(CLI::App* command, std::string* out, const std::string& help) {
  return command->add_option("--out", *out, help);
}

CLI::Option* AddSeedFlag(CLI::App* command, unsigned* seed, const std::string& help) {
  return command->add_option("--seed", *seed, help)->capture_default_str();
}

CLI::Option* AddFrictionFlag(CLI::App* command, std::vector<std::string>* friction, const std::string& help) {
  return command->add_option("--friction", *friction, help)->delimiter(',')->capture_default_str();
}

CLI::Option* AddBasePoseFlag(CLI::App* command, BasePose* pose) {
  return command
      ->add_option_function<std::string>(
          "--base-pose",
          [pose](const std::string& text) {
            std::string why;
            if (!ParseBasePose(text, pose, &why)) throw CLI::ValidationError(why);
          },
          "The robot's base in the world, x,y,z [m] and roll,pitch,yaw [rad] (URDF rpy); gravity along the "
          "world's -z (ceiling: 0,0,2,3.14159265,0,0)")
      ->type_name("X,Y,Z,R,P,Y");
}

CLI::Option* AddSceneFlag(CLI::App* command, std::string* scene) {
  return command
      ->add_option("--scene", *scene,
                   "The cell: JSON {\"floor\": true, \"obstacles\": [boxes, cylinders, spheres, meshes with "
                   "world poses]}; the clearance keeps the links off them")
      ->type_name("FILE");
}

CLI::Option* AddReportFlag(CLI::App* command, bool* report) {
  return command->add_flag("--report", *report, kReportHelp);
}

}  // namespace idbench::cli
