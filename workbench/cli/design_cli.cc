// `idbench design`: an excitation trajectory (Fourier series) optimised for
// identification within the joint limits; its flags fill DesignCommandOptions.
// Ctrl-C stops the search and keeps the best feasible design so far.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "ctrl_c_stop.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/reports/design_report.h"
#include "idbench/workbench/reports/report_command.h"
#include "output_files.h"

namespace idbench::cli {
namespace {

// Fields of DesignCommandOptions and DesignOptions named in messages.
constexpr FieldFlag kDesignSpellings[] = {
    {"harmonics", "--harmonics"},     {"f0", "--f0"},
    {"samples", "--samples"},         {"starts", "--starts"},
    {"threads", "--threads"},         {"max_evaluations", "--max-evaluations"},
    {"max_seconds", "--max-time"},    {"margin", "--margin"},
    {"clearance", "--clearance"},     {"ramp_seconds", "--ramp"},
    {"home", "--home"},               {"limits", "--limits"},
    {"model", "--model"},             {"criterion", "--criterion"},
    {"algorithm", "--algorithm"},     {"csv_rate_hz", "--rate"},
    {"csv_columns", "--csv-columns"},
    {"transmission", "--transmission"}, {"given", "--given"}};

struct DesignFlags {
  DesignCommandOptions options;
  bool report = false;   // --report
};

int DesignCommand(const DesignCommandOptions& options, const UrdfLoadOptions& load, bool with_report,
                  const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  std::optional<Transmission> from_urdf;
  const RobotModel model = LoadRobotOrThrow(options.robot, load, &from_urdf);
  if (!options.IsValidFor(model, &why)) return context.UsageError(why);
  std::optional<DesignCommandReport> searched;
  {
    const CtrlCStop ctrl_c;  // Ctrl-C: stop and keep the best feasible design so far
    searched.emplace(RunDesign(model, options, ctrl_c.flag(), from_urdf));
  }
  const DesignCommandReport& report = *searched;
  const std::string& explanation = report.result.infeasibility.explanation;
  switch (report.status()) {
    case DesignStatus::kFeasible:
      break;
    case DesignStatus::kNoMotionPossible:  // settings that admit no motion are wrong input: nothing written
      return context.UsageError(explanation);
    case DesignStatus::kInfeasible:  // the search ran, or the cell has no room: design.json explains it
    case DesignStatus::kNoRoom: {
      OutputFiles out(options.out_dir);
      out.Add("design.json", FormatDesignJson(model, options, report));
      out.Write();
      std::fprintf(stderr, "idbench: error: %s\n", context.FlagSpelling(explanation).c_str());
      return kExitFailure;
    }
    case DesignStatus::kNotExcited: {  // a motion within the limits that leaves parameters unexcited
      // Nothing written, unless asked: then design.json (status not_excited) and the motion found.
      std::fprintf(stderr, "idbench: error: %s\n", context.FlagSpelling(explanation).c_str());
      if (!options.write_trajectory_anyway) return kExitFailure;
      OutputFiles out(options.out_dir);
      out.Add("design.json", FormatDesignJson(model, options, report));
      out.Add("trajectory.json", FormatTrajectoryJson(report.result.trajectory));
      out.Add("trajectory.csv", FormatDesignTrajectoryCsv(model, options, report));
      out.Write();
      std::fprintf(stderr, "idbench: wrote %s with the diagnostics and, as asked, trajectory.json and trajectory.csv\n",
                   out.Path("design.json").c_str());
      return kExitFailure;
    }
  }
  std::fputs(context.FlagSpelling(FormatDesignSummary(options, report)).c_str(), stdout);
  OutputFiles out(options.out_dir);
  // What a controller would run only from a usable design (or when asked).
  const bool usable = report.result.usable();
  out.Add("design.json", FormatDesignJson(model, options, report));
  if (usable || options.write_trajectory_anyway) {
    out.Add("trajectory.json", FormatTrajectoryJson(report.result.trajectory));
    out.Add("trajectory.csv", FormatDesignTrajectoryCsv(model, options, report));
  }
  if (with_report) out.AddReport(MakeDesignReportContent(model, options, report));
  if (!usable) {
    out.Write();
    std::fprintf(stderr, "idbench: error: the design is not usable: %s; wrote %s with the diagnostics%s\n",
                 report.result.Rejection().c_str(), out.Path("design.json").c_str(),
                 options.write_trajectory_anyway ? " and, as asked, trajectory.json and trajectory.csv"
                                                 : ", no trajectory (--write-trajectory-anyway writes it)");
    return kExitFailure;
  }
  out.Write("wrote " + out.Path("trajectory.json").string() + ", trajectory.csv and design.json" +
            (with_report ? ", report.html and report.pdf" : ""));
  return 0;
}

// The flags of the search itself (DesignCommandOptions::design).
void AddSearchFlags(CLI::App* command, DesignOptions* design) {
  command->add_option("--harmonics", design->harmonics, "Harmonics H per joint")->capture_default_str();
  command->add_option("--f0", design->f0, "Base frequency [Hz]")->capture_default_str();
  command->add_option("--duration", design->duration, "Duration [s]; 0 = one period 1/f0")->capture_default_str();
  command->add_flag("--rest-to-rest", design->rest_to_rest, "Start and end at rest (adds a quintic)");
  command->add_option("--samples", design->samples, "Samples per duration in the criterion and limits")
      ->capture_default_str();
  command->add_option("--starts", design->starts, "Random starts")->capture_default_str();
  AddSeedFlag(command, &design->seed, "Seed of the first start (start k uses seed + k)");
  command->add_option("--threads", design->threads, "Threads running starts")->capture_default_str();
  command->add_option("--max-evaluations", design->max_evaluations, "Criterion evaluations per start")
      ->capture_default_str();
  command->add_option("--max-time", design->max_seconds, "Wall-time limit [s]; 0 = none")->capture_default_str();
  command->add_option("--margin", design->margin, "Limits tightened by this fraction during the search")
      ->capture_default_str();
  command->add_option("--clearance", design->clearance,
                      "Minimum distance between links no joint connects, to the floor z = 0 and to the --scene's "
                      "obstacles [m]; -1: off")
      ->capture_default_str();
}

}  // namespace

CliCommand AddDesignCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kDesignSpellings);
  context->AddSpellings(kLogReadingSpellings);
  auto flags = std::make_shared<DesignFlags>();
  DesignCommandOptions& design = flags->options;
  design.command_line = context->command_line();
  CLI::App* command = app->add_subcommand(
      "design", "Optimise an excitation trajectory (Fourier series) for identification, within the joint limits");
  AddRobotFlags(command, &design.robot, context->robot_load());
  AddEnumFlag(command, "--model", &design.model, kIdentificationModelNames,
              "Identification model: torque (base parameters) or per-body");
  AddFrictionFlag(command, &design.friction, "Friction terms of the torque model");
  AddEnumFlag(command, "--criterion", &design.criterion, kDesignCriterionNames,
              "cond, cond-normalised, logdet or hybrid (default: cond; per-body: logdet)");
  AddEnumFlag(command, "--algorithm", &design.algorithm, kDesignAlgorithmNames,
              "slsqp, mma (gradient), cobyla, sbplx (derivative-free)");
  AddSearchFlags(command, &design.design);
  command->add_option("--limits", design.limits,
                      "Limits JSON {\"joints\": [{q_min, q_max, qd_max, qdd_max, tau_max}], "
                      "\"actuators\": [{qd_max, tau_max}] (optional, motor side, with --transmission)}");
  command->add_option("--transmission", design.transmission,
                      "Transmission of the --limits file's actuators: urdf (the robot URDF's) or a JSON/YAML file "
                      "({\"reduction\": [...]}, {\"actuator_from_joint\": [[...]]} or a log description)");
  AddSceneFlag(command, &design.scene);
  AddBasePoseFlag(command, &design.design.base_pose);
  command->add_option("--rate", design.csv_rate_hz, "Sample rate of trajectory.csv [Hz]")->capture_default_str();
  AddEnumFlag(command, "--csv-columns", &design.csv_columns, kTrajectoryCsvColumnsNames,
              "trajectory.csv columns: q or q,qd,qdd");
  command->add_option("--ramp", design.design.ramp_seconds,
                      "Rest-to-rest ramps from and to the home pose in trajectory.csv and the re-check [s]; 0: none")
      ->capture_default_str();
  command->add_option("--home", design.home, "Home pose q1,...,qn [rad] the motion oscillates about")->delimiter(',');
  // Sequential design: the logs the robot already has, read as identify reads --data.
  command
      ->add_option("--given", design.given,
                   "A motion the robot already has (repeatable): a joint log identify reads, or a designed "
                   "trajectory (.json/.csv); the criterion is that of their union with the new motion")
      ->allow_extra_args(false);
  AddLogReadingFlags(command, &design.given_reading.format, nullptr, {}, &design.given_reading.filter,
                     &design.given_reading.max_gap_s);
  AddDriveGainsFlag(command, &design.given_reading.format);
  command->add_flag("--quiet", design.quiet, "No progress on stderr");
  command->add_flag("--write-trajectory-anyway", design.write_trajectory_anyway,
                    "Write trajectory.json/.csv even when the design is not usable (infeasible or no progress); "
                    "still exits 1");
  AddReportFlag(command, &flags->report);
  AddOutFlag(command, &design.out_dir)->capture_default_str();
  return {command, [flags, context] {
            return DesignCommand(flags->options, *context->robot_load(), flags->report, *context);
          }};
}

}  // namespace idbench::cli
