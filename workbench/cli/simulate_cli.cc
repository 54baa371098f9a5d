// `idbench simulate`: an experiment in Bullet, written as a joint log (CSV);
// its flags fill SimulateOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/logs/joint_log_csv_writer.h"

namespace idbench::cli {
namespace {

// Fields of SimulateOptions named in messages.
constexpr FieldFlag kSimulateSpellings[] = {{"paper_accel_deg_s2", "--accel"},
                                            {"out", "--out"},
                                            {"motor_viscous", "--motor-viscous"},
                                            {"motor_coulomb", "--motor-coulomb"},
                                            {"motor_rotor_inertia", "--motor-rotor-inertia"},
                                            {"transmission", "--transmission"},
                                            {"tau_noise_bandwidth_hz", "--tau-noise-bandwidth"},
                                            {"controller", "--controller"},
                                            {"noise_preset", "--noise-preset"},
                                            {"q_noise", "--q-noise"}};

struct SimulateFlags {
  SimulateOptions options;
  bool no_derivatives = false;  // --no-derivatives: sensors.record_derivatives = false
  NoisePreset noise_preset = NoisePreset::kNone;  // --noise-preset: sensors.q_noise, tau_noise
};

int SimulateCommand(const SimulateOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  std::optional<Transmission> from_urdf;
  const RobotModel model = LoadRobotOrThrow(options.robot, load, &from_urdf);
  if (!options.sensors.IsValid(model.n_dof(), options.dt, &why)) return context.UsageError(why);
  const std::optional<Transmission> transmission = SimulateTransmission(options, model.n_dof(), from_urdf);
  const std::filesystem::path path(options.out);
  if (path.has_parent_path()) EnsureOutputDirectory(path.parent_path());
  if (!options.controller.empty()) {
    const ClosedLoopLog closed = SimulateClosedLoopLog(model, options);
    WriteFileAtomically(path, FormatJointLogCsv(closed.log, &closed.q_ref));
    const double tracking = (closed.log.q - closed.q_ref).cwiseAbs().maxCoeff();
    std::printf("simulated %s along '%s' for %g s under the controller %s: %d samples at %g Hz, largest measured "
                "tracking error %.3g rad; wrote %s\n",
                model.name().c_str(), options.trajectory.c_str(), closed.log.n_samples() / options.sensors.rate_hz,
                options.controller.c_str(), closed.log.n_samples(), options.sensors.rate_hz, tracking, path.c_str());
    if (const auto lost = LostTrackingWarning(model, closed)) std::fprintf(stderr, "idbench: warning: %s\n", lost->c_str());
    return 0;
  }
  if (!transmission) {
    const JointLog log = SimulateJointLog(model, options);
    WriteFileAtomically(path, FormatJointLogCsv(log));
    std::printf("simulated %s along '%s' for %g s: %d samples at %g Hz; wrote %s\n", model.name().c_str(),
                options.trajectory.c_str(), log.n_samples() / options.sensors.rate_hz, log.n_samples(),
                options.sensors.rate_hz, path.c_str());
    return 0;
  }
  // Motor side: the CSV and, beside it, the description that names its transmission.
  const MotorSideLog log = SimulateMotorSideLog(model, *transmission, options);
  const std::filesystem::path description = options.Outputs().back();
  WriteFileAtomically(path, FormatMotorSideLogCsv(log));
  WriteFileAtomically(description, FormatMotorSideLogDescription(log, path.filename().string()));
  const int n_samples = log.motor.n_samples();
  std::printf("simulated %s along '%s' for %g s: %d samples at %g Hz on the motor side; wrote %s and its "
              "description %s (read it as --data %s)\n",
              model.name().c_str(), options.trajectory.c_str(), n_samples / options.sensors.rate_hz, n_samples,
              options.sensors.rate_hz, path.c_str(), description.c_str(), description.c_str());
  return 0;
}

}  // namespace

CliCommand AddSimulateCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kSimulateSpellings);
  auto flags = std::make_shared<SimulateFlags>();
  SimulateOptions& simulate = flags->options;
  CLI::App* command = app->add_subcommand("simulate", "Simulate an experiment in Bullet and write the joint log (CSV)");
  AddRobotFlags(command, &simulate.robot, context->robot_load());
  command->add_option("--trajectory", simulate.trajectory,
                      "Built-in motion (paper, general, general-reversed) or trajectory file (.json, .csv)")
      ->capture_default_str();
  command->add_option("--accel", simulate.paper_accel_deg_s2, "Acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  command->add_option("--duration", simulate.duration, "Simulated time of a built-in motion [s]")
      ->capture_default_str();
  command->add_option("--dt", simulate.dt, "Simulation step [s]")->capture_default_str();
  command->add_option("--rate", simulate.sensors.rate_hz, "Sample rate of the log [Hz]")->capture_default_str();
  command->add_option("--tau-noise", simulate.sensors.tau_noise,
                      "Torque noise sigma [N m]: one value, or one per joint")
      ->delimiter(',');
  command->add_option("--tau-noise-bandwidth", simulate.sensors.tau_noise_bandwidth_hz,
                      "Torque noise low-pass coloured to this band [Hz], sigma unchanged; 0 = white")
      ->capture_default_str();
  command->add_option("--q-noise", simulate.sensors.q_noise, "Position noise sigma [rad]")->capture_default_str();
  AddEnumFlag(command, "--noise-preset", &flags->noise_preset, kNoisePresetNames,
              "BIRDy's noise levels: low (position 1e-4 deg, torque 0.05 N m) or high (1e-2 deg, 0.10 N m); "
              "instead of --q-noise and --tau-noise");
  command->add_option("--encoder-resolution", simulate.sensors.q_resolution, "Encoder quantum [rad]; 0 = none")
      ->capture_default_str();
  command->add_flag("--no-derivatives", flags->no_derivatives,
                    "Log only t, q, tau (as a real robot); identify then filters q for qd, qdd");
  command->add_option("--transmission", simulate.transmission,
                      "Write a motor-side log (qm, qdm, qdd, taum) and its description (.json beside --out): "
                      "'urdf' for the robot's <transmission> elements, or a .json/.yaml file with {\"reduction\": "
                      "[...]} or {\"actuator_from_joint\": [[...]], \"joint_offset\": [...]}");
  command->add_option("--motor-viscous", simulate.motor_viscous,
                      "Each motor's viscous friction [N m s/rad], on its own velocity: one value, or one per motor")
      ->delimiter(',');
  command->add_option("--motor-coulomb", simulate.motor_coulomb,
                      "Each motor's Coulomb friction [N m]: one value, or one per motor")
      ->delimiter(',');
  command->add_option("--motor-rotor-inertia", simulate.motor_rotor_inertia,
                      "Each motor's rotor inertia [kg m^2]: one value, or one per motor")
      ->delimiter(',');
  command->add_option("--controller", simulate.controller,
                      "Closed loop: a controller file {\"kp\": [...], \"kd\": [...], \"ki\": [...], \"tau_max\": "
                      "[...], \"feedforward\": \"model\"} (one value or one per joint) whose PID, at --rate, tracks "
                      "--trajectory from the measured q; the log adds the reference qr1..qrn");
  AddBasePoseFlag(command, &simulate.base_pose);
  AddSeedFlag(command, &simulate.sensors.seed);
  AddOutFlag(command, &simulate.out, "Joint-log CSV to write")->capture_default_str();
  return {command, [flags, context] {
            flags->options.sensors.record_derivatives = !flags->no_derivatives;
            std::string why;
            if (!ApplyNoisePreset(flags->noise_preset, &flags->options.sensors, &why)) {
              return context->UsageError(why);
            }
            return SimulateCommand(flags->options, *context->robot_load(), *context);
          }};
}

}  // namespace idbench::cli
