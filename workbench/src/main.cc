// idbench: design robot identification experiments, simulate them in Bullet,
// identify dynamic parameters. Exit codes: 0 ok, 2 bad usage, 1 failure.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "atomic_file.h"
#include "idbench/engine/paper6r.h"
#include "log_csv.h"
#include "run_command.h"

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"idbench: a workbench for robot excitation design and dynamic parameter identification"};

  idbench::RunOptions run;
  for (int i = 0; i < argc; ++i) run.command_line += (i ? " " : "") + std::string(i ? argv[i] : "idbench");
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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return UsageError(e.what());
  }

  try {
    if (run_cmd->parsed()) return RunCommand(run);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench: error: %s\n", e.what());
    return kExitFailure;
  }
  return UsageError("a subcommand is required (run); see idbench --help");
}
