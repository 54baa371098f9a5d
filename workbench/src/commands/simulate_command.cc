#include "idbench/workbench/commands/simulate_command.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench {

SimulationOptions SimulateOptions::simulation() const {
  SimulationOptions sim;
  sim.dt = dt;
  sim.duration = duration;
  return sim;
}

bool SimulateOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  std::string sim_why;
  if (!simulation().IsValid(&sim_why)) return fail(sim_why);
  if (!std::isfinite(paper_accel_deg_s2) || paper_accel_deg_s2 <= 0.0)
    return fail("paper_accel_deg_s2: must be > 0 deg/s^2, got " + std::to_string(paper_accel_deg_s2));
  if (!base_pose.IsValid(why)) return false;
  if (std::string out_why; !IsUsableOutputFile(out, "out", &out_why)) return fail(out_why);
  return true;
}

JointLog SimulateJointLog(const RobotModel& loaded, const SimulateOptions& options) {
  const RobotModel model = MountRobot(loaded, options.base_pose);  // gravity seen from the base
  std::string why;
  if (!options.sensors.IsValid(model.n_dof(), options.dt, &why)) throw std::invalid_argument("sensors: " + why);
  const BuiltinMotionOptions builtin{.duration = options.duration,
                                     .paper_qdd = options.paper_accel_deg_s2 * std::numbers::pi / 180.0};
  const std::unique_ptr<Trajectory> motion = LoadTrajectoryArg(options.trajectory, model, builtin);
  SimulationOptions simulation = options.simulation();
  simulation.duration = motion->duration();  // a file's own
  return Measure(Simulate(model, *motion, simulation), options.sensors);
}

}  // namespace idbench
