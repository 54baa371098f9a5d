// `idbench montecarlo`: the identification error under torque noise, seeded
// trials against the predicted covariance; its flags fill MonteCarloOptions.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "log_reading_flags.h"
#include "idbench/workbench/commands/montecarlo_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {
namespace {

// Fields of MonteCarloOptions named in messages (beside the shared ones).
constexpr FieldFlag kMonteCarloSpellings[] = {{"trials", "--trials"}, {"samples", "--samples"}, {"tau_noise", "--tau-noise"}, {"tau_noise_bandwidth_hz", "--tau-noise-bandwidth"}, {"trajectory", "--trajectory"}};

struct MonteCarloFlags {
  MonteCarloOptions options;
  bool no_derivatives = false;  // --no-derivatives: options.record_derivatives = false
};

int MonteCarloCommand(const MonteCarloOptions& options, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = LoadRobotOrThrow(options.robot, load);
  const MonteCarloReport report = RunMonteCarlo(model, options);
  // A motion that does not excite every base parameter is wrong input: nothing printed or written.
  if (report.status == MonteCarloStatus::kNotExcited) return context.UsageError(report.message);
  std::fputs(FormatMonteCarloTables(options, report).c_str(), stdout);
  if (!options.out_dir.empty()) {
    const std::filesystem::path dir(options.out_dir);
    EnsureOutputDirectory(dir);
    WriteFileAtomically(dir / "montecarlo.json", FormatMonteCarloJson(options, report));
    std::printf("wrote %s\n", (dir / "montecarlo.json").c_str());
  }
  return 0;
}

}  // namespace

CliCommand AddMonteCarloCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kMonteCarloSpellings);
  auto flags = std::make_shared<MonteCarloFlags>();
  MonteCarloOptions& montecarlo = flags->options;
  montecarlo.command_line = context->command_line();
  CLI::App* command = app->add_subcommand(
      "montecarlo", "Identification error under torque noise: seeded trials against the predicted covariance");
  AddRobotFlags(command, &montecarlo.robot, context->robot_load(), "Built-in robot or URDF file");
  command->add_option("--trajectory", montecarlo.trajectory, "Identification motion: built-in or .json/.csv file")
      ->capture_default_str();
  command->add_option("--held-out", montecarlo.held_out, "Validation motion: built-in or .json/.csv file")
      ->capture_default_str();
  command->add_option("--duration", montecarlo.duration, "Experiment length [s]")->capture_default_str();
  command->add_option("--samples", montecarlo.samples, "Samples over the duration")->capture_default_str();
  command->add_option("--tau-noise", montecarlo.tau_noise,
                      "Torque noise sigma per joint, or one for all [N m]; default: 0.5 on joints 1-3, 0.05 on the others")
      ->delimiter(',');
  command->add_option("--tau-noise-bandwidth", montecarlo.tau_noise_bandwidth_hz,
                      "Torque noise low-pass coloured to this band [Hz], sigma unchanged; 0 = white")
      ->capture_default_str();
  command->add_flag("--no-derivatives", flags->no_derivatives,
                    "Identify each trial from t, q, tau as a robot logs them: qd, qdd from the filtered q");
  AddFilterFlags(command, &montecarlo.filter);
  AddFrictionFlag(command, &montecarlo.friction, "Friction terms");
  command->add_option("--trials", montecarlo.trials, "Number of trials")->capture_default_str();
  AddSeedFlag(command, &montecarlo.seed);
  AddOutFlag(command, &montecarlo.out_dir, "Directory for montecarlo.json (optional)");
  return {command, [flags, context] {
            flags->options.record_derivatives = !flags->no_derivatives;
            return MonteCarloCommand(flags->options, *context->robot_load(), *context);
          }};
}

}  // namespace idbench::cli
