// idbench: design robot identification experiments, simulate them in Bullet,
// identify dynamic parameters. Exit codes: 0 ok, 2 bad usage, 1 failure.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "atomic_file.h"
#include "identify_command.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/robot_library.h"
#include "joint_log_csv.h"
#include "log_csv.h"
#include "montecarlo_command.h"
#include "run_command.h"
#include "simulate_command.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

int UsageError(const std::string& message) {
  std::fprintf(stderr, "idbench: error: %s\n", message.c_str());
  return kExitUsage;
}

int RunCommand(const idbench::RunOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = idbench::MakePaper6r();
  const idbench::RunReport report = idbench::RunExperiment(model, options);
  std::fputs(idbench::FormatRunTables(options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  idbench::WriteFilesAtomically({{dir / "log.csv", idbench::FormatLogCsv(model, report.log)},
                                 {dir / "results.json", idbench::FormatRunResultsJson(options, report)}});
  std::printf("wrote %s and %s\n", (dir / "results.json").c_str(), (dir / "log.csv").c_str());
  return 0;
}

// A robot by name or path; warnings go to stderr.
idbench::RobotModel LoadRobotOrThrow(const std::string& name_or_path) {
  idbench::UrdfLoadResult loaded = idbench::LoadRobot(name_or_path);
  for (const std::string& w : loaded.warnings) std::fprintf(stderr, "idbench: warning: %s\n", w.c_str());
  return std::move(loaded.model);
}

int SimulateCommand(const idbench::SimulateOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot);
  if (!options.sensors.IsValid(model.n_dof(), options.dt, &why)) return UsageError(why);
  const idbench::JointLog log = idbench::SimulateJointLog(model, options);
  const std::filesystem::path path(options.out);
  if (path.has_parent_path()) idbench::EnsureOutputDirectory(path.parent_path());
  idbench::WriteFileAtomically(path, idbench::FormatJointLogCsv(log));
  std::printf("simulated %s along '%s' for %g s: %d samples at %g Hz; wrote %s\n", model.name().c_str(),
              options.trajectory.c_str(), options.duration, log.n_samples(), options.sensors.rate_hz,
              path.c_str());
  return 0;
}

int IdentifyCommand(const idbench::IdentifyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot);
  const idbench::IdentifyReport report = idbench::RunIdentify(model, options);
  std::fputs(idbench::FormatIdentifyTables(model, options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  idbench::WriteFilesAtomically({{dir / "identified.json", idbench::FormatIdentifiedJson(model, options, report)},
                                 {dir / "identified.urdf", idbench::FormatIdentifiedUrdf(model, options, report)}});
  std::printf("wrote %s and %s\n", (dir / "identified.json").c_str(), (dir / "identified.urdf").c_str());
  return 0;
}

int MonteCarloCommand(const idbench::MonteCarloOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot);
  const idbench::MonteCarloReport report = idbench::RunMonteCarlo(model, options);
  std::fputs(idbench::FormatMonteCarloTables(options, report).c_str(), stdout);
  if (!options.out_dir.empty()) {
    const std::filesystem::path dir(options.out_dir);
    idbench::EnsureOutputDirectory(dir);
    idbench::WriteFileAtomically(dir / "montecarlo.json", idbench::FormatMonteCarloJson(options, report));
    std::printf("wrote %s\n", (dir / "montecarlo.json").c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"idbench: a workbench for robot excitation design and dynamic parameter identification"};

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(i ? argv[i] : "idbench");

  idbench::RunOptions run;
  run.command_line = command_line;
  CLI::App* run_cmd = app.add_subcommand("run", "Run the paper's experiment: simulate, identify, compare with the truth");
  run_cmd->add_option("--robot", run.robot, "Robot (built-in: paper6r)")->capture_default_str();
  run_cmd->add_option("--motion", run.motion, "paper: hinges 1, 2 accelerate, others locked; general: all six move")
      ->capture_default_str();
  run_cmd->add_option("--accel", run.accel_deg_s2, "Hinge acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  run_cmd->add_option("--duration", run.duration, "Simulated time [s]")->capture_default_str();
  run_cmd->add_option("--dt", run.dt, "Simulation step [s]")->capture_default_str();
  CLI::Option* samples =
      run_cmd->add_option("--samples", run.sample_times, "Sample times t1,t2,... [s]")->delimiter(',');
  run_cmd->add_flag("--all-samples", run.all_samples, "Identify from every simulation step")->excludes(samples);
  run_cmd->add_option("--out", run.out_dir, "Output directory (created if missing, never wiped)")
      ->capture_default_str();


  idbench::SimulateOptions simulate;
  CLI::App* simulate_cmd =
      app.add_subcommand("simulate", "Simulate an experiment in Bullet and write the joint log (CSV)");
  simulate_cmd->add_option("--robot", simulate.robot, "Built-in robot (paper6r, puma560) or URDF file")
      ->capture_default_str();
  simulate_cmd->add_option("--trajectory", simulate.trajectory, "Built-in motion: paper, general, general-reversed")
      ->capture_default_str();
  simulate_cmd->add_option("--accel", simulate.paper_accel_deg_s2, "Acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  simulate_cmd->add_option("--duration", simulate.duration, "Simulated time [s]")->capture_default_str();
  simulate_cmd->add_option("--dt", simulate.dt, "Simulation step [s]")->capture_default_str();
  simulate_cmd->add_option("--rate", simulate.sensors.rate_hz, "Sample rate of the log [Hz]")->capture_default_str();
  simulate_cmd->add_option("--tau-noise", simulate.sensors.tau_noise,
                           "Torque noise sigma [N m]: one value, or one per joint")->delimiter(',');
  simulate_cmd->add_option("--q-noise", simulate.sensors.q_noise, "Position noise sigma [rad]")->capture_default_str();
  simulate_cmd->add_option("--encoder-resolution", simulate.sensors.q_resolution,
                           "Encoder quantum [rad]; 0 = none")->capture_default_str();
  bool no_derivatives = false;
  simulate_cmd->add_flag("--no-derivatives", no_derivatives,
                         "Log only t, q, tau (as a real robot); identify then filters q for qd, qdd");
  simulate_cmd->add_option("--seed", simulate.sensors.seed, "Noise seed")->capture_default_str();
  simulate_cmd->add_option("--out", simulate.out, "Joint-log CSV to write")->capture_default_str();

  idbench::IdentifyOptions identify;
  identify.command_line = command_line;
  CLI::App* identify_cmd = app.add_subcommand("identify", "Identify base parameters from a joint log (CSV)");
  identify_cmd->add_option("--robot", identify.robot, "Built-in robot (paper6r, puma560) or URDF file")
      ->capture_default_str();
  identify_cmd->add_option("--data", identify.data, "Joint-log CSV (t, q*, [qd*, qdd*], tau*)")->required();
  identify_cmd->add_option("--model", identify.model, "torque (per-body needs hinge wrenches: idbench run)")
      ->capture_default_str();
  identify_cmd->add_option("--estimator", identify.estimator, "ols, wls or pc (physically consistent)")
      ->capture_default_str();
  identify_cmd->add_option("--friction", identify.friction, "Friction terms: none or viscous,coulomb,offset,rotor")
      ->delimiter(',')->capture_default_str();
  identify_cmd->add_option("--coulomb-smoothing", identify.coulomb_smoothing,
                           "Coulomb tanh(qd/v) transition velocity v [rad/s]; 0 = sign")->capture_default_str();
  identify_cmd->add_option("--filter-cutoff", identify.filter.cutoff_hz,
                           "Butterworth cutoff for logs without qd/qdd [Hz]")->capture_default_str();
  identify_cmd->add_option("--filter-order", identify.filter.order, "Butterworth order")->capture_default_str();
  identify_cmd->add_option("--decimate", identify.filter.decimation, "Keep every k-th sample after filtering")
      ->capture_default_str();
  identify_cmd->add_option("--validate", identify.validate, "Held-out joint log to validate on");
  identify_cmd->add_option("--out", identify.out_dir, "Output directory (created if missing, never wiped)")
      ->capture_default_str();

  idbench::MonteCarloOptions montecarlo;
  montecarlo.command_line = command_line;
  CLI::App* montecarlo_cmd = app.add_subcommand(
      "montecarlo", "Identification error under torque noise: seeded trials against the predicted covariance");
  montecarlo_cmd->add_option("--robot", montecarlo.robot, "Built-in robot or URDF file")->capture_default_str();
  montecarlo_cmd->add_option("--trajectory", montecarlo.trajectory, "Identification motion")->capture_default_str();
  montecarlo_cmd->add_option("--held-out", montecarlo.held_out, "Validation motion")->capture_default_str();
  montecarlo_cmd->add_option("--duration", montecarlo.duration, "Experiment length [s]")->capture_default_str();
  montecarlo_cmd->add_option("--samples", montecarlo.samples, "Samples over the duration")->capture_default_str();
  montecarlo_cmd->add_option("--tau-noise", montecarlo.tau_noise, "Torque noise sigma per joint [N m]")
      ->delimiter(',')->capture_default_str();
  montecarlo_cmd->add_option("--friction", montecarlo.friction, "Friction terms")->delimiter(',')->capture_default_str();
  montecarlo_cmd->add_option("--trials", montecarlo.trials, "Number of trials")->capture_default_str();
  montecarlo_cmd->add_option("--seed", montecarlo.seed, "Noise seed")->capture_default_str();
  montecarlo_cmd->add_option("--out", montecarlo.out_dir, "Directory for montecarlo.json (optional)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return UsageError(e.what());
  }

  try {
    if (run_cmd->parsed()) return RunCommand(run);
    if (simulate_cmd->parsed()) {
      simulate.sensors.record_derivatives = !no_derivatives;
      return SimulateCommand(simulate);
    }
    if (identify_cmd->parsed()) return IdentifyCommand(identify);
    if (montecarlo_cmd->parsed()) return MonteCarloCommand(montecarlo);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench: error: %s\n", e.what());
    return kExitFailure;
  }
  return UsageError("a subcommand is required (run, simulate, identify, montecarlo); see idbench --help");
}
