// idbench: design robot identification experiments, simulate them in Bullet,
// identify dynamic parameters. Exit codes, one rule for every command (README
// "Exit codes"): 0 ok; 2 the options or an input file are wrong (a usage
// error, or std::invalid_argument from reading or checking the inputs), nothing
// written; 1 it ran and failed (any other error), nothing written.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/commands/compare_command.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/reports/design_report.h"
#include "idbench/workbench/commands/gains_command.h"
#include "idbench/gui/gui_command.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/robot_library.h"
#include "idbench/engine/input_file.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/simulation_log_csv.h"
#include "idbench/workbench/commands/montecarlo_command.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/reports/report_command.h"
#include "idbench/workbench/commands/run_command.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/version.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// Library messages name option fields (time_window); the command line says
// its flags (--time-window).
std::string FlagSpelling(std::string message) {
  static const std::pair<const char*, const char*> kFields[] = {
      {"loaded_time_window", "--loaded-time-window"}, {"validate_window", "--validate-window"},
      {"time_window", "--time-window"},               {"drive_gains", "--drive-gains"},
      {"angle_unit", "--angle-unit"}};
  for (const auto& [field, flag] : kFields) {
    const std::string f(field);
    for (size_t at = message.find(f); at != std::string::npos; at = message.find(f, at + 1)) {
      // A word of its own (not part of a path such as /tmp/time_window.csv).
      const std::string before = " (,", after = " :,);";
      const bool word = (at == 0 || before.find(message[at - 1]) != std::string::npos) &&
                        (at + f.size() == message.size() || after.find(message[at + f.size()]) != std::string::npos);
      if (word) message.replace(at, f.size(), flag);
    }
  }
  return message;
}

int UsageError(const std::string& message) {
  std::fprintf(stderr, "idbench: error: %s\n", FlagSpelling(message).c_str());
  return kExitUsage;
}

// Thrown for a usage error found after parsing; main() exits with kExitUsage.
struct UsageException : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// --lock JOINT=VALUE (repeatable, or comma-separated) and --tip LINK: how a
// URDF robot file becomes a chain (see idbench/engine/urdf.h). For every
// subcommand that takes --robot.
void AddRobotLoadOptions(CLI::App* command, idbench::UrdfLoadOptions* options) {
  command
      ->add_option_function<std::vector<std::string>>(
          "--lock",
          [options](const std::vector<std::string>& locks) {
            for (const std::string& lock : locks) {
              std::string why;
              if (!idbench::AddJointLock(lock, options, &why)) throw CLI::ValidationError(why);
            }
          },
          "URDF: hold a joint at a value [rad, or m if prismatic], e.g. panda_finger_joint1=0.04; joints off the "
          "chain are held at 0 by default")
      ->delimiter(',')
      ->type_name("JOINT=VALUE");
  command->add_option("--tip", options->tip_link,
                      "URDF: the arm's last link, when the file branches (default: the end of its one revolute chain)")
      ->type_name("LINK");
}

int RunCommand(const idbench::RunOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = idbench::MakePaper6r();
  const idbench::RunReport report = idbench::RunExperiment(model, options);
  std::fputs(idbench::FormatRunTables(options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "log.csv", idbench::FormatLogCsv(model, report.log)},
      {dir / "results.json", idbench::FormatRunResultsJson(options, report)}};
  if (options.report) {
    const idbench::ReportContent content =
        idbench::MakeRunReportContent(model, options, report, idbench::RenderRunFigurePng(model, options));
    for (auto& file : idbench::FormatReportFiles(content, dir)) files.push_back(std::move(file));
  } else if (options.figure) {
    files.emplace_back(dir / "figure.png", idbench::RenderRunFigurePng(model, options));
  }
  idbench::WriteFilesAtomically(files);
  std::printf("wrote %s and %s%s%s\n", (dir / "results.json").c_str(), (dir / "log.csv").c_str(),
              options.figure || options.report ? (" and " + (dir / "figure.png").string()).c_str() : "",
              options.report ? (" and " + (dir / "report.html").string() + ", report.pdf").c_str() : "");
  return 0;
}

// A robot by name or path; warnings go to stderr. --lock/--tip with a
// built-in robot is a usage error.
idbench::RobotModel LoadRobotOrThrow(const std::string& name_or_path, const idbench::UrdfLoadOptions& load) {
  const std::vector<std::string> builtins = idbench::BuiltinRobotNames();
  if (!load.empty() && std::find(builtins.begin(), builtins.end(), name_or_path) != builtins.end()) {
    throw UsageException("--lock and --tip apply to URDF files, not to the built-in robot '" + name_or_path + "'");
  }
  idbench::UrdfLoadResult loaded = idbench::LoadRobot(name_or_path, load);
  for (const std::string& w : loaded.warnings) std::fprintf(stderr, "idbench: warning: %s\n", w.c_str());
  return std::move(loaded.model);
}

int SimulateCommand(const idbench::SimulateOptions& options, const idbench::UrdfLoadOptions& load) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  if (!options.sensors.IsValid(model.n_dof(), options.dt, &why)) return UsageError(why);
  const idbench::JointLog log = idbench::SimulateJointLog(model, options);
  const std::filesystem::path path(options.out);
  if (path.has_parent_path()) idbench::EnsureOutputDirectory(path.parent_path());
  idbench::WriteFileAtomically(path, idbench::FormatJointLogCsv(log));
  std::printf("simulated %s along '%s' for %g s: %d samples at %g Hz; wrote %s\n", model.name().c_str(),
              options.trajectory.c_str(), log.n_samples() / options.sensors.rate_hz, log.n_samples(), options.sensors.rate_hz,
              path.c_str());
  return 0;
}

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::fprintf(stderr, "idbench: warning: %s\n", FlagSpelling(w).c_str());
}

int IdentifyCommand(const idbench::IdentifyOptions& options, const idbench::UrdfLoadOptions& load, bool with_report) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  if (!options.format.IsValidFor(model.n_dof(), &why)) return UsageError(why);
  if (!options.plausibility.IsValidFor(model, &why)) return UsageError(why);
  const idbench::IdentifyReport report = idbench::RunIdentify(model, options);
  PrintWarnings(report.warnings);
  std::fputs(idbench::FormatIdentifyTables(model, options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  // The robot model (identified.urdf, joints.yaml) only when its verdict is
  // fit to load, or the user accepts it (--write-unverified); the diagnostics always.
  const bool model_files = idbench::WritesRobotModel(options, report);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "identified.json", idbench::FormatIdentifiedJson(model, options, report)}};
  if (model_files) {
    files.emplace_back(dir / "identified.urdf", idbench::FormatIdentifiedUrdf(model, options, report));
    files.emplace_back(dir / "joints.yaml", idbench::FormatJointDynamicsYaml(model, options, report));
  }
  if (with_report) {
    for (auto& file : idbench::FormatReportFiles(idbench::MakeIdentifyReportContent(model, options, report), dir))
      files.push_back(std::move(file));
  }
  idbench::WriteFilesAtomically(files);
  std::printf("wrote %s%s%s\n", (dir / "identified.json").c_str(),
              model_files ? (", " + (dir / "identified.urdf").string() + " and joints.yaml").c_str() : "",
              with_report ? (" and " + (dir / "report.html").string() + ", report.pdf").c_str() : "");
  const std::string refused = idbench::RefusedModelMessage(options, report, idbench::OptionNames::kCommandLine);
  if (refused.empty()) return 0;
  if (options.write_unverified) {
    std::fprintf(stderr, "idbench: warning: %s\n", refused.c_str());
    return 0;
  }
  std::fprintf(stderr, "idbench: error: %s\n", refused.c_str());
  return kExitFailure;
}

int GainsCommand(const idbench::GainsOptions& options, const idbench::UrdfLoadOptions& load) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  if (!options.preparation().format.IsValidFor(model.n_dof(), &why)) return UsageError(why);
  const idbench::GainsReport report = idbench::RunGains(model, options);
  PrintWarnings(report.warnings);
  std::fputs(idbench::FormatGainsTable(model, options, report).c_str(), stdout);
  if (report.estimate.status != idbench::DriveGainStatus::kEstimated) {  // the table above says why; nothing written
    std::fprintf(stderr, "idbench: error: %s\n", FlagSpelling(report.estimate.message).c_str());
    return kExitFailure;
  }
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  idbench::WriteFileAtomically(dir / "gains.json", idbench::FormatGainsJson(model, options, report));
  std::printf("wrote %s\n", (dir / "gains.json").c_str());
  return 0;
}

int MonteCarloCommand(const idbench::MonteCarloOptions& options, const idbench::UrdfLoadOptions& load) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
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

int RenderCommand(const idbench::RenderOptions& options, const idbench::UrdfLoadOptions& load) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  const std::unique_ptr<idbench::Trajectory> trajectory = idbench::MakeRenderTrajectory(model, options);
  const idbench::PoseFigureOptions figure = options.figure();
  if (!figure.IsValid(trajectory->duration(), &why)) return UsageError(why);
  const std::string png = idbench::RenderPoseFigurePng(model, *trajectory, figure);
  const std::filesystem::path path(options.out);
  if (path.has_parent_path()) idbench::EnsureOutputDirectory(path.parent_path());
  idbench::WriteFileAtomically(path, png);
  std::printf("rendered %s along '%s' at %zu instants (%dx%d px); wrote %s\n", model.name().c_str(),
              options.trajectory.c_str(), figure.times.size(), figure.columns() * figure.panel_width,
              figure.rows() * figure.panel_height, path.c_str());
  return 0;
}

// Ctrl-C during a design: stop and keep the best feasible design so far.
std::atomic<bool> g_stop_requested{false};
extern "C" void RequestStop(int) { g_stop_requested = true; }

int DesignCommand(const idbench::DesignCommandOptions& options, const idbench::UrdfLoadOptions& load, bool with_report) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  if (!options.IsValidFor(model, &why)) return UsageError(why);
  std::signal(SIGINT, RequestStop);
  const std::filesystem::path dir(options.out_dir);
  const idbench::DesignCommandReport report = [&] {
    try {
      return idbench::RunDesign(model, options, &g_stop_requested);
    } catch (const idbench::InfeasibleDesign& e) {  // the search ran: design.json explains it
      if (!e.before_search()) {
        idbench::EnsureOutputDirectory(dir);
        idbench::WriteFileAtomically(dir / "design.json", idbench::FormatInfeasibleDesignJson(model, options, e));
      }
      throw;
    }
  }();
  std::signal(SIGINT, SIG_DFL);
  std::fputs(idbench::FormatDesignSummary(options, report).c_str(), stdout);
  idbench::EnsureOutputDirectory(dir);
  // What a controller would run only from a usable design (or when asked).
  const bool usable = report.result.usable();
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "design.json", idbench::FormatDesignJson(model, options, report)}};
  if (usable || options.write_trajectory_anyway) {
    files.push_back({dir / "trajectory.json", idbench::FormatTrajectoryJson(report.result.trajectory)});
    files.push_back({dir / "trajectory.csv", idbench::FormatDesignTrajectoryCsv(model, options, report)});
  }
  if (with_report) {
    for (auto& file : idbench::FormatReportFiles(idbench::MakeDesignReportContent(model, options, report), dir))
      files.push_back(std::move(file));
  }
  idbench::WriteFilesAtomically(files);
  if (!usable) {
    std::fprintf(stderr, "idbench: error: the design is not usable: %s; wrote %s with the diagnostics%s\n",
                 report.result.Rejection().c_str(), (dir / "design.json").c_str(),
                 options.write_trajectory_anyway ? " and, as asked, trajectory.json and trajectory.csv"
                                                 : ", no trajectory (--write-trajectory-anyway writes it)");
    return kExitFailure;
  }
  std::printf("wrote %s, trajectory.csv and design.json%s\n", (dir / "trajectory.json").c_str(),
              with_report ? ", report.html and report.pdf" : "");
  return 0;
}

int CompareCommand(const idbench::CompareOptions& options, const idbench::UrdfLoadOptions& load, bool with_report) {
  std::string why;
  if (!options.IsValid(&why)) return UsageError(why);
  const idbench::RobotModel model = LoadRobotOrThrow(options.robot, load);
  const idbench::CompareReport report = idbench::RunCompare(model, options);
  std::fputs(idbench::FormatCompareTable(options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  idbench::EnsureOutputDirectory(dir);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "compare.json", idbench::FormatCompareJson(options, report)},
      {dir / "compare.csv", idbench::FormatCompareCsv(report)}};
  if (with_report) {
    for (auto& file : idbench::FormatReportFiles(idbench::MakeCompareReportContent(options, report), dir))
      files.push_back(std::move(file));
  }
  idbench::WriteFilesAtomically(files);
  std::printf("wrote %s and compare.csv%s\n", (dir / "compare.json").c_str(),
              with_report ? ", report.html and report.pdf" : "");
  return 0;
}

// `idbench report --out DIR`: the report of the run whose results.json is in DIR.
int ReportCommand(const std::string& out_dir) {
  if (out_dir.empty()) return UsageError("--out: empty path");
  const std::filesystem::path dir(out_dir);
  const std::filesystem::path results = dir / "results.json";
  if (!std::filesystem::is_regular_file(results)) {
    throw std::invalid_argument(results.string() + ": no such file; `idbench report` reads the results.json of " +
                             "`idbench run --out " + out_dir + "` (for identify, use `idbench identify --report`)");
  }
  idbench::RunOptions options = idbench::RunOptionsFromResultsJson(idbench::ReadInputFile(results), results.string());
  options.out_dir = out_dir;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(results.string() + ": " + why);
  const idbench::RobotModel model = idbench::MakePaper6r();
  const idbench::RunReport report = idbench::RunExperiment(model, options);
  const idbench::ReportContent content =
      idbench::MakeRunReportContent(model, options, report, idbench::RenderRunFigurePng(model, options));
  idbench::WriteFilesAtomically(idbench::FormatReportFiles(content, dir));
  std::printf("wrote %s and %s\n", (dir / "report.html").c_str(), (dir / "report.pdf").c_str());
  return 0;
}

// The options that say how a joint log is read and conditioned, shared by
// identify and gains (README "Joint logs").
void AddLogReadingOptions(CLI::App* command, idbench::JointLogFormat* format, std::vector<std::string>* friction,
                          double* coulomb_smoothing, idbench::LogFilterOptions* filter, double* max_gap_s) {
  // Split here, not by CLI11 (which drops empty items: `t,q1,,q3` would read
  // as t,q1,q3 and blame a missing q2); an empty item is then named.
  command->add_option_function<std::string>("--columns", [format](const std::string& list) {
        format->columns.clear();
        size_t start = 0;
        for (size_t comma = list.find(','); ; comma = list.find(',', start)) {
          format->columns.push_back(list.substr(start, comma == std::string::npos ? comma : comma - start));
          if (comma == std::string::npos) break;
          start = comma + 1;
        }
      },
                      "Column names in file order: t,q1..q6,qd1..qd6,i1..i6,_ ... (with a header of idbench's names: agree with "
                      "it, or name a subset, matched by name; other header names are renamed in order)")
      ->type_name("NAMES");
  command->add_option("--angle-unit", format->angle_unit, "Unit of q, qd, qdd in the logs: rad or deg")
      ->capture_default_str();
  command->add_option("--friction", *friction, "Friction terms: none or viscous,coulomb,offset,rotor")
      ->delimiter(',')->capture_default_str();
  command->add_option("--coulomb-smoothing", *coulomb_smoothing,
                      "Coulomb tanh(qd/v) transition velocity v [rad/s]; 0 = sign")->capture_default_str();
  command->add_option("--filter-cutoff", filter->cutoff_hz, "Butterworth cutoff for logs without qd/qdd [Hz]")
      ->capture_default_str();
  command->add_option("--filter-order", filter->order, "Butterworth order")->capture_default_str();
  command->add_option("--max-gap", *max_gap_s, "Longest time step resampled [s]; 0 = 10 median steps")
      ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"idbench: a workbench for robot excitation design and dynamic parameter identification"};
  app.set_version_flag("--version", std::string("idbench ") + idbench::Version() + " (git " + idbench::GitRevision() + ")",
                       "Print the version and the git revision built from, then exit");

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(i ? argv[i] : "idbench");

  idbench::RunOptions run;
  run.command_line = command_line;
  CLI::App* run_cmd = app.add_subcommand("run", "Run the paper's experiment: simulate, identify, compare with the truth");
  run_cmd->add_option("--robot", run.robot, "Robot (built-in: paper6r)")->capture_default_str();
  run_cmd->add_option("--motion,--trajectory", run.motion,
                      "paper: hinges 1, 2 accelerate, others locked; general: all six move; or a .json/.csv file")
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
  bool run_no_figure = false;
  run_cmd->add_flag("--no-figure", run_no_figure, "Do not render figure.png (the poses at the paper's instants)");
  run_cmd->add_flag("--report", run.report, "Also write report.html, report.pdf and the plots");


  // --lock/--tip of whichever subcommand runs (AddRobotLoadOptions).
  idbench::UrdfLoadOptions robot_load;

  idbench::SimulateOptions simulate;
  CLI::App* simulate_cmd =
      app.add_subcommand("simulate", "Simulate an experiment in Bullet and write the joint log (CSV)");
  simulate_cmd->add_option("--robot", simulate.robot, "Built-in robot (paper6r, puma560) or URDF file")
      ->capture_default_str();
  AddRobotLoadOptions(simulate_cmd, &robot_load);
  simulate_cmd->add_option("--trajectory", simulate.trajectory,
                           "Built-in motion (paper, general, general-reversed) or trajectory file (.json, .csv)")
      ->capture_default_str();
  simulate_cmd->add_option("--accel", simulate.paper_accel_deg_s2, "Acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  simulate_cmd->add_option("--duration", simulate.duration, "Simulated time of a built-in motion [s]")
      ->capture_default_str();
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
  AddRobotLoadOptions(identify_cmd, &robot_load);
  identify_cmd->add_option("--data", identify.data, "Joint-log CSV (t, q*, [qd*, qdd*], tau*)")->required();
  identify_cmd->add_option("--model", identify.model, "torque (per-body needs hinge wrenches: idbench run)")
      ->capture_default_str();
  identify_cmd->add_option("--estimator", identify.estimator, "ols, wls or pc (physically consistent)")
      ->capture_default_str();
  AddLogReadingOptions(identify_cmd, &identify.format, &identify.friction, &identify.coulomb_smoothing,
                       &identify.filter, &identify.max_gap_s);
  identify_cmd->add_option("--decimate", identify.filter.decimation, "Keep every k-th sample after filtering")
      ->capture_default_str();
  identify_cmd->add_option("--validate", identify.validate, "Held-out joint log to validate on");
  identify_cmd->add_option("--validate-window", identify.validate_window,
                           "Score only T0 <= t <= T1 of --validate: T0,T1 [s] (the whole file's error is shown beside)")
      ->delimiter(',');
  // Currents and a part of the log (README "Joint logs").
  identify_cmd->add_option("--drive-gains", identify.format.drive_gains,
                           "Drive gains K1,...,Kn [N m/A]: tau = K*i from the current columns i1..in")->delimiter(',');
  identify_cmd->add_option("--time-window", identify.time_window, "Use only T0 <= t <= T1 of --data: T0,T1 [s]")
      ->delimiter(',');
  std::vector<double> identify_mass_range{identify.plausibility.mass_factor_min, identify.plausibility.mass_factor_max};
  identify_cmd->add_option("--mass-range", identify_mass_range,
                           "Physically consistent estimate: each link's mass within LO,HI x the robot file's")
      ->delimiter(',')->expected(2)->capture_default_str();
  identify_cmd->add_option("--total-mass", identify.plausibility.total_mass,
                           "Total mass of the moving links [kg]; 0: no bound beyond the links'")->capture_default_str();
  identify_cmd->add_option("--total-mass-tolerance", identify.plausibility.total_mass_tolerance,
                           "Fraction the total mass may differ from --total-mass")->capture_default_str();
  std::string identify_com_bound = "geometry";
  identify_cmd->add_option("--com-bound", identify_com_bound,
                           "geometry: each centre of mass inside the box around its link's shapes; none")
      ->capture_default_str();
  identify_cmd->add_option("--prior-weight", identify.plausibility.prior_weight,
                           "Weight of the robot file's values as a prior (fraction of the OLS residual)")
      ->capture_default_str();
  identify_cmd->add_option("--cost-tolerance", identify.plausibility.cost_tolerance,
                           "The physically consistent estimate is a robot model only within this fraction above the "
                           "OLS optimum's cost")->capture_default_str();
  identify_cmd->add_flag("--write-unverified", identify.write_unverified,
                         "Write identified.urdf and joints.yaml even when the estimate is not fit to load (exit 0)");
  identify_cmd->add_option("--out", identify.out_dir, "Output directory (created if missing, never wiped)")
      ->capture_default_str();
  bool identify_report = false;
  identify_cmd->add_flag("--report", identify_report, "Also write report.html, report.pdf and the plots");

  idbench::GainsOptions gains;
  gains.command_line = command_line;
  CLI::App* gains_cmd = app.add_subcommand(
      "gains", "Drive gains (torque per motor current) from an unloaded log and one with a known payload mass");
  gains_cmd->add_option("--robot", gains.robot, "Built-in robot (paper6r, puma560) or URDF file")->capture_default_str();
  AddRobotLoadOptions(gains_cmd, &robot_load);
  gains_cmd->add_option("--data", gains.data, "Unloaded log with motor currents i1..in")->required();
  gains_cmd->add_option("--loaded", gains.loaded, "Log of the same robot with the payload on the last link")->required();
  gains_cmd->add_option("--payload-mass", gains.payload_mass, "Known payload mass [kg]")->required();
  AddLogReadingOptions(gains_cmd, &gains.format, &gains.friction, &gains.coulomb_smoothing, &gains.filter,
                       &gains.max_gap_s);
  gains_cmd->add_option("--time-window", gains.time_window, "Use only T0 <= t <= T1 of --data: T0,T1 [s]")
      ->delimiter(',');
  gains_cmd->add_option("--loaded-time-window", gains.loaded_time_window,
                        "Use only T0 <= t <= T1 of --loaded: T0,T1 [s]")->delimiter(',');
  gains_cmd->add_option("--out", gains.out_dir, "Output directory for gains.json (created if missing, never wiped)")
      ->capture_default_str();

  idbench::MonteCarloOptions montecarlo;
  montecarlo.command_line = command_line;
  CLI::App* montecarlo_cmd = app.add_subcommand(
      "montecarlo", "Identification error under torque noise: seeded trials against the predicted covariance");
  montecarlo_cmd->add_option("--robot", montecarlo.robot, "Built-in robot or URDF file")->capture_default_str();
  AddRobotLoadOptions(montecarlo_cmd, &robot_load);
  montecarlo_cmd->add_option("--trajectory", montecarlo.trajectory, "Identification motion: built-in or .json/.csv file")
      ->capture_default_str();
  montecarlo_cmd->add_option("--held-out", montecarlo.held_out, "Validation motion: built-in or .json/.csv file")
      ->capture_default_str();
  montecarlo_cmd->add_option("--duration", montecarlo.duration, "Experiment length [s]")->capture_default_str();
  montecarlo_cmd->add_option("--samples", montecarlo.samples, "Samples over the duration")->capture_default_str();
  montecarlo_cmd->add_option("--tau-noise", montecarlo.tau_noise, "Torque noise sigma per joint [N m]")
      ->delimiter(',')->capture_default_str();
  montecarlo_cmd->add_option("--friction", montecarlo.friction, "Friction terms")->delimiter(',')->capture_default_str();
  montecarlo_cmd->add_option("--trials", montecarlo.trials, "Number of trials")->capture_default_str();
  montecarlo_cmd->add_option("--seed", montecarlo.seed, "Noise seed")->capture_default_str();
  montecarlo_cmd->add_option("--out", montecarlo.out_dir, "Directory for montecarlo.json (optional)");

  idbench::RenderOptions render;
  CLI::App* render_cmd =
      app.add_subcommand("render", "Render the robot at chosen instants of a motion as one labelled PNG (headless)");
  render_cmd->add_option("--robot", render.robot, "Built-in robot (paper6r, puma560) or URDF file")
      ->capture_default_str();
  AddRobotLoadOptions(render_cmd, &robot_load);
  render_cmd->add_option("--trajectory", render.trajectory,
                         "Built-in motion (paper, general, general-reversed) or trajectory file (.json, .csv)")
      ->capture_default_str();
  render_cmd->add_option("--accel", render.paper_accel_deg_s2, "Acceleration of the paper motion [deg/s^2]")
      ->capture_default_str();
  render_cmd->add_option("--duration", render.duration, "Length of the built-in motion [s]")->capture_default_str();
  render_cmd->add_option("--times", render.times, "Instants t1,t2,... [s], one panel each")->delimiter(',')
      ->capture_default_str();
  render_cmd->add_option("--layout", render.layout, "grid (rows of 4) or strip (one row)")->capture_default_str();
  render_cmd->add_option("--size", render.size, "One panel, WxH [px]")->capture_default_str();
  render_cmd->add_option("--out", render.out, "PNG file to write")->capture_default_str();

  idbench::DesignCommandOptions design;
  design.command_line = command_line;
  CLI::App* design_cmd = app.add_subcommand(
      "design", "Optimise an excitation trajectory (Fourier series) for identification, within the joint limits");
  design_cmd->add_option("--robot", design.robot, "Built-in robot (paper6r, puma560) or URDF file")
      ->capture_default_str();
  AddRobotLoadOptions(design_cmd, &robot_load);
  design_cmd->add_option("--model", design.model, "Identification model: torque (base parameters) or per-body")
      ->capture_default_str();
  design_cmd->add_option("--friction", design.friction, "Friction terms of the torque model")
      ->delimiter(',')->capture_default_str();
  design_cmd->add_option("--criterion", design.criterion,
                         "cond, cond-normalised, logdet or hybrid (default: cond; per-body: logdet)");
  design_cmd->add_option("--algorithm", design.algorithm, "slsqp, mma (gradient), cobyla, sbplx (derivative-free)")
      ->capture_default_str();
  design_cmd->add_option("--harmonics", design.design.harmonics, "Harmonics H per joint")->capture_default_str();
  design_cmd->add_option("--f0", design.design.f0, "Base frequency [Hz]")->capture_default_str();
  design_cmd->add_option("--duration", design.design.duration, "Duration [s]; 0 = one period 1/f0")
      ->capture_default_str();
  design_cmd->add_flag("--rest-to-rest", design.design.rest_to_rest, "Start and end at rest (adds a quintic)");
  design_cmd->add_option("--samples", design.design.samples, "Samples per duration in the criterion and limits")
      ->capture_default_str();
  design_cmd->add_option("--starts", design.design.starts, "Random starts")->capture_default_str();
  design_cmd->add_option("--seed", design.design.seed, "Seed of the first start (start k uses seed + k)")
      ->capture_default_str();
  design_cmd->add_option("--threads", design.design.threads, "Threads running starts")->capture_default_str();
  design_cmd->add_option("--max-evaluations", design.design.max_evaluations, "Criterion evaluations per start")
      ->capture_default_str();
  design_cmd->add_option("--max-time", design.design.max_seconds, "Wall-time limit [s]; 0 = none")
      ->capture_default_str();
  design_cmd->add_option("--margin", design.design.margin, "Limits tightened by this fraction during the search")
      ->capture_default_str();
  design_cmd->add_option("--clearance", design.design.clearance,
                         "Minimum distance between links no joint connects and to the ground z = 0 [m]; -1: off")
      ->capture_default_str();
  design_cmd->add_option("--limits", design.limits, "Limits JSON {\"joints\": [{q_min, q_max, qd_max, qdd_max, tau_max}]}");
  design_cmd->add_option("--rate", design.csv_rate_hz, "Sample rate of trajectory.csv [Hz]")->capture_default_str();
  design_cmd->add_option("--csv-columns", design.csv_columns, "trajectory.csv columns: q or q,qd,qdd")
      ->capture_default_str();
  design_cmd->add_option("--ramp", design.design.ramp_seconds,
                         "Rest-to-rest ramps from and to the home pose in trajectory.csv and the re-check [s]; 0: none")
      ->capture_default_str();
  design_cmd->add_option("--home", design.home, "Home pose q1,...,qn [rad] the motion oscillates about")
      ->delimiter(',');
  design_cmd->add_flag("--quiet", design.quiet, "No progress on stderr");
  design_cmd->add_flag("--write-trajectory-anyway", design.write_trajectory_anyway,
                       "Write trajectory.json/.csv even when the design is not usable (infeasible or no progress); "
                       "still exits 1");
  bool design_report = false;
  design_cmd->add_flag("--report", design_report, "Also write report.html, report.pdf and the plots");
  design_cmd->add_option("--out", design.out_dir, "Output directory (created if missing, never wiped)")
      ->capture_default_str();

  idbench::CompareOptions compare;
  compare.command_line = command_line;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare", "Identifiability of motions side by side: cond, log det, %sigma, Monte-Carlo error on Bullet data");
  compare_cmd->add_option("trajectories", compare.trajectories, "Motions: built-in names or .json/.csv files")
      ->required();
  compare_cmd->add_option("--robot", compare.robot, "Built-in robot or URDF file")->capture_default_str();
  AddRobotLoadOptions(compare_cmd, &robot_load);
  compare_cmd->add_option("--model", compare.model, "torque or per-body")->capture_default_str();
  compare_cmd->add_option("--friction", compare.friction, "Friction terms of the torque model")
      ->delimiter(',')->capture_default_str();
  compare_cmd->add_option("--duration", compare.duration, "Length of built-in motions [s]")->capture_default_str();
  compare_cmd->add_option("--samples", compare.samples, "Samples per motion")->capture_default_str();
  compare_cmd->add_option("--tau-noise,--noise", compare.tau_noise, "Torque noise sigma per joint [N m] (torque model)")
      ->delimiter(',')->capture_default_str();
  compare_cmd->add_option("--wrench-noise", compare.wrench_noise, "Hinge force, moment noise sigma [N, N m] (per-body)")
      ->delimiter(',')->capture_default_str();
  compare_cmd->add_option("--clearance", compare.clearance, "Minimum link clearance in the limits check [m]; -1: off")
      ->capture_default_str();
  compare_cmd->add_option("--trials", compare.trials, "Monte-Carlo trials per motion")->capture_default_str();
  compare_cmd->add_option("--seed", compare.seed, "Noise seed")->capture_default_str();
  compare_cmd->add_option("--out", compare.out_dir, "Output directory for compare.json and compare.csv")
      ->capture_default_str();
  bool compare_report = false;
  compare_cmd->add_flag("--report", compare_report, "Also write report.html, report.pdf and the plots");

  std::string report_dir;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "Write report.html and report.pdf (figure, tables, plots) for the results of `idbench run` in DIR");
  report_cmd->add_option("--out", report_dir, "Directory holding results.json; the report is written there")
      ->required();

  idbench::gui::GuiCommandOptions gui;
  std::string gui_size = "1280x720";
  CLI::App* gui_cmd = app.add_subcommand(
      "gui", "The workbench window (GLFW + OpenGL 3); --headless draws it offscreen, driven by --script");
  gui_cmd->add_option("--robot", gui.robot, "Built-in robot (paper6r, puma560) or URDF file")->capture_default_str();
  gui_cmd->add_option("--out", gui.out_dir, "Directory for logs and exports")->capture_default_str();
  gui_cmd->add_flag("--headless", gui.headless, "No window: OSMesa, scripted input");
  gui_cmd->add_option("--script", gui.script, "Headless: steps (click, set, wait, frames, screenshot), one a line");
  gui_cmd->add_option("--screenshot", gui.screenshot, "Write the last frame as a PNG");
  gui_cmd->add_option("--frames", gui.frames, "Window: close after N frames (0: when closed)");
  gui_cmd->add_option("--size", gui_size, "Window size WxH [px]")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return UsageError(e.what());
  }

  try {
    if (run_cmd->parsed()) {
      run.figure = !run_no_figure;
      return RunCommand(run);
    }
    if (simulate_cmd->parsed()) {
      simulate.sensors.record_derivatives = !no_derivatives;
      return SimulateCommand(simulate, robot_load);
    }
    if (identify_cmd->parsed()) {
      identify.plausibility.mass_factor_min = identify_mass_range[0];
      identify.plausibility.mass_factor_max = identify_mass_range[1];
      if (identify_com_bound != "geometry" && identify_com_bound != "none")
        return UsageError("--com-bound: expected geometry or none, got '" + identify_com_bound + "'");
      identify.plausibility.com_in_geometry = identify_com_bound == "geometry";
      return IdentifyCommand(identify, robot_load, identify_report);
    }
    if (gains_cmd->parsed()) return GainsCommand(gains, robot_load);
    if (montecarlo_cmd->parsed()) return MonteCarloCommand(montecarlo, robot_load);
    if (render_cmd->parsed()) return RenderCommand(render, robot_load);
    if (report_cmd->parsed()) return ReportCommand(report_dir);
    if (design_cmd->parsed()) return DesignCommand(design, robot_load, design_report);
    if (compare_cmd->parsed()) return CompareCommand(compare, robot_load, compare_report);
    if (gui_cmd->parsed()) {
      if (std::sscanf(gui_size.c_str(), "%dx%d", &gui.width, &gui.height) != 2)
        return UsageError("--size: expected WxH, got '" + gui_size + "'");
      std::string why;
      if (!gui.IsValid(&why)) return UsageError(why);
      return idbench::gui::RunGuiCommand(gui);
    }
  } catch (const std::invalid_argument& e) {  // also UsageException: the input is wrong
    return UsageError(e.what());
  } catch (const idbench::InfeasibleDesign& e) {
    // Settings that admit no motion are wrong input (nothing ran); a search
    // that found nothing feasible ran and failed.
    if (e.before_search()) return UsageError(e.what());
    std::fprintf(stderr, "idbench: error: %s\n", e.what());
    return kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench: error: %s\n", e.what());
    return kExitFailure;
  }
  return UsageError("a subcommand is required (run, simulate, identify, gains, montecarlo, design, compare, render, report, gui); see idbench --help");
}
