// `idbench identify`: base parameters (and the physically consistent
// estimate) from a joint log; its flags fill IdentifyOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli_command.h"
#include "ctrl_c_stop.h"
#include "common_flags.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/reports/report_command.h"

namespace idbench::cli {
namespace {

// Fields of IdentifyOptions named in messages.
constexpr FieldFlag kIdentifySpellings[] = {
    {"validate_window", "--validate-window"}, {"time_window", "--time-window"}, {"drive_gains", "--drive-gains"},
    {"friction_side", "--friction-side"}, {"data", "--data"}, {"model", "--model"}, {"estimator", "--estimator"},
    {"controller", "--controller"}, {"reference", "--reference"},
    // PlausibilitySettings, as the library names them.
    {"plausibility.com_in_geometry = false", "--com-bound none"},
    {"plausibility.mass_factor_min, plausibility.mass_factor_max", "--mass-range"},
    {"plausibility.total_mass_tolerance", "--total-mass-tolerance"}, {"plausibility.total_mass", "--total-mass"},
    {"plausibility.prior_weight", "--prior-weight"}, {"plausibility.cost_tolerance", "--cost-tolerance"},
    {"write_unverified", "--write-unverified"}};

struct IdentifyFlags {
  IdentifyOptions options;
  std::vector<double> mass_range;     // --mass-range LO,HI: plausibility.mass_factor_min, _max
  std::string com_bound = "geometry"; // --com-bound: plausibility.com_in_geometry
  bool report = false;                // --report
  std::vector<std::string> data;      // --data (repeatable): data, then more_data
};

int IdentifyCommand(IdentifyOptions options, const UrdfLoadOptions& load, bool with_report,
                    const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  // The URDF's <transmission>, for actuator-side columns (a log description's
  // wins); the robot mounted as base_pose says (gravity in its base frame).
  const RobotModel model =
      MountRobot(LoadRobotOrThrow(options.robot, load, &options.format.transmission), options.base_pose);
  if (!options.format.IsValidFor(model.n_dof(), &why)) return context.UsageError(why);
  if (!options.plausibility.IsValidFor(model, &why)) return context.UsageError(why);
  // Ctrl-C: stop at the next block of samples (or after the solve), write nothing.
  std::string stage;
  const IdentifyReport report = [&] {
    const CtrlCStop ctrl_c;
    IdentifyControl control;
    control.stop = ctrl_c.flag();
    control.progress = [&stage](const IdentifyProgress& p) { stage = p.stage; };
    return RunIdentify(model, options, control);
  }();
  if (report.status == IdentifyStatus::kCancelled) {
    std::fprintf(stderr, "idbench: error: identify stopped (Ctrl-C) while %s: nothing written\n", stage.c_str());
    return kExitFailure;
  }
  context.PrintWarnings(report.warnings);
  std::fputs(FormatIdentifyTables(model, options, report).c_str(), stdout);
  const std::filesystem::path dir(options.out_dir);
  EnsureOutputDirectory(dir);
  // The robot model (identified.urdf, identified.xml, joints.yaml) only when its verdict is
  // fit to load, or the user accepts it (--write-unverified); the diagnostics always.
  const bool model_files = WritesRobotModel(options, report);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {dir / "identified.json", FormatIdentifiedJson(model, options, report)}};
  if (model_files) {
    files.emplace_back(dir / "identified.urdf", FormatIdentifiedUrdf(model, options, report));
    files.emplace_back(dir / "joints.yaml", FormatJointDynamicsYaml(model, options, report));
    files.emplace_back(dir / "identified.xml", FormatIdentifiedMjcf(model, options, report));
  }
  if (with_report) {
    for (auto& file : FormatReportFiles(MakeIdentifyReportContent(model, options, report), dir))
      files.push_back(std::move(file));
  }
  WriteFilesAtomically(files);
  std::printf("wrote %s%s%s\n", (dir / "identified.json").c_str(),
              model_files ? (", " + (dir / "identified.urdf").string() + ", identified.xml and joints.yaml").c_str() : "",
              with_report ? (" and " + (dir / "report.html").string() + ", report.pdf").c_str() : "");
  // A closed-loop estimator that did not converge: the files hold its last
  // estimate (and say so); the run failed.
  if (report.closed_loop && !report.closed_loop->converged) return kExitFailure;
  const std::string refused = context.FlagSpelling(RefusedModelMessage(options, report));
  if (refused.empty()) return 0;
  if (options.write_unverified) {
    std::fprintf(stderr, "idbench: warning: %s\n", refused.c_str());
    return 0;
  }
  std::fprintf(stderr, "idbench: error: %s\n", refused.c_str());
  return kExitFailure;
}

// The flags of the physically consistent estimate (IdentifyOptions::plausibility).
void AddPlausibilityFlags(CLI::App* command, IdentifyFlags* flags) {
  PlausibilitySettings& plausibility = flags->options.plausibility;
  flags->mass_range = {plausibility.mass_factor_min, plausibility.mass_factor_max};
  command->add_option("--mass-range", flags->mass_range,
                      "Physically consistent estimate: each link's mass within LO,HI x the robot file's")
      ->delimiter(',')->expected(2)->capture_default_str();
  command->add_option("--total-mass", plausibility.total_mass,
                      "Total mass of the moving links [kg]; 0: no bound beyond the links'")->capture_default_str();
  command->add_option("--total-mass-tolerance", plausibility.total_mass_tolerance,
                      "Fraction the total mass may differ from --total-mass")->capture_default_str();
  command->add_option("--com-bound", flags->com_bound,
                      "geometry: each centre of mass inside the box around its link's shapes; none")
      ->capture_default_str();
  command->add_option("--prior-weight", plausibility.prior_weight,
                      "Weight of the robot file's values as a prior (fraction of the OLS residual)")
      ->capture_default_str();
  command->add_option("--cost-tolerance", plausibility.cost_tolerance,
                      "The physically consistent estimate is a robot model only within this fraction above the "
                      "OLS optimum's cost")->capture_default_str();
}

}  // namespace

CliCommand AddIdentifyCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kIdentifySpellings);
  context->AddSpellings(kLogReadingSpellings);
  auto flags = std::make_shared<IdentifyFlags>();
  IdentifyOptions& identify = flags->options;
  identify.command_line = context->command_line();
  CLI::App* command = app->add_subcommand("identify", "Identify base parameters from a joint log (CSV)");
  AddRobotFlags(command, &identify.robot, context->robot_load());
  AddBasePoseFlag(command, &identify.base_pose);
  // One value per --data; repeated: several logs of the robot, identified together.
  command
      ->add_option("--data", flags->data,
                   "Joint log: CSV (t, q*, [qd*, qdd*], tau*), log description (.json/.yaml) or ROS 2 bag; "
                   "repeat for several logs of the robot, each read and filtered on its own, stacked into one fit")
      ->required()
      ->allow_extra_args(false);
  AddEnumFlag(command, "--model", &identify.model, kIdentificationModelNames,
              "torque (per-body needs hinge wrenches: idbench run)");
  AddEnumFlag(command, "--estimator", &identify.estimator, kTorqueEstimatorNames,
              "ols, wls, pc (physically consistent), tls (total least squares: noisy regressor), irls "
              "(iteratively reweighted, robust to outliers), iv (instrumental variables) or didim: iv and didim "
              "re-simulate the closed loop (--controller, --reference)");
  command->add_option("--controller", identify.controller,
                      "iv, didim: the robot's controller file (as simulate --controller reads it)");
  command->add_option("--reference", identify.reference,
                      "iv, didim: the reference the robot tracked: a built-in motion (10 s) or a trajectory file");
  AddLogReadingFlags(command, &identify.format, &identify.friction,
                     {&identify.coulomb_smoothing, &identify.coulomb_min_speed}, &identify.filter, &identify.max_gap_s);
  AddEnumFlag(command, "--friction-side", &identify.friction_side, kFrictionSideNames,
              "joint, or actuator: friction and rotor terms per motor, through the transmission "
              "(log description or URDF <transmission>)");
  command->add_option("--decimate", identify.filter.decimation, "Keep every k-th sample after filtering")
      ->capture_default_str();
  command->add_option("--validate", identify.validate, "Held-out joint log to validate on");
  command->add_option("--validate-window", identify.validate_window,
                      "Score only T0 <= t <= T1 of --validate: T0,T1 [s] (the whole file's error is shown beside)")
      ->delimiter(',');
  // Currents and a part of the log (docs/formats/joint-logs.md).
  AddDriveGainsFlag(command, &identify.format);
  command->add_option("--time-window", identify.time_window, "Use only T0 <= t <= T1 of --data: T0,T1 [s]")
      ->delimiter(',');
  AddPlausibilityFlags(command, flags.get());
  command->add_flag("--write-unverified", identify.write_unverified,
                    "Write identified.urdf and joints.yaml even when the estimate is not fit to load (exit 0)");
  AddOutFlag(command, &identify.out_dir)->capture_default_str();
  AddReportFlag(command, &flags->report);
  return {command, [flags, context] {
            IdentifyOptions& options = flags->options;
            options.data = flags->data.front();
            options.more_data.assign(flags->data.begin() + 1, flags->data.end());
            options.plausibility.mass_factor_min = flags->mass_range[0];
            options.plausibility.mass_factor_max = flags->mass_range[1];
            if (flags->com_bound != "geometry" && flags->com_bound != "none")
              return context->UsageError("--com-bound: expected geometry or none, got '" + flags->com_bound + "'");
            options.plausibility.com_in_geometry = flags->com_bound == "geometry";
            return IdentifyCommand(options, *context->robot_load(), flags->report, *context);
          }};
}

}  // namespace idbench::cli
