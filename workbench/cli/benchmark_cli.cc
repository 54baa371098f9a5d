// `idbench benchmark`: Monte-Carlo trials of the closed loop under noise
// presets, each identified by every estimator (benchmark_command.h); its
// flags fill BenchmarkOptions. `idbench benchmark merge DIR... --out DIR`
// joins the shards of a run (--shard K/N) into the single run's result.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/engine/input_file.h"
#include "idbench/workbench/commands/benchmark_command.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/reports/plots.h"

namespace idbench::cli {
namespace {

// Fields of BenchmarkOptions named in messages (beside the shared ones).
constexpr FieldFlag kBenchmarkSpellings[] = {{"trials", "--trials"},         {"estimators", "--estimators"},
                                             {"presets", "--preset"},        {"threads", "--threads"},
                                             {"shard", "--shard"},           {"controller", "--controller"},
                                             {"trajectory", "--trajectory"}, {"merge", "benchmark merge"}};

struct BenchmarkFlags {
  BenchmarkOptions options;
  std::vector<std::string> estimators{"ols", "wls", "tls", "irls", "iv", "didim"};  // --estimators
  std::vector<std::string> presets{"low"};                                          // --preset
  std::string shard;                                                                // --shard K/N
  std::vector<std::string> merge_dirs;  // benchmark merge DIR...
  std::string merge_out;                // benchmark merge --out
};

// An enum value from a flag's text: false with *why naming `field` (the
// library's field, e.g. "estimators") and the choices.
template <typename Enum, std::size_t N>
bool ParseListItem(const std::string& text, const EnumNames<Enum, N>& names, const std::string& field, Enum* value,
                   std::string* why) {
  if (names.Parse(text, value, why)) return true;
  *why = field + why->substr(names.field.size());
  return false;
}

// The flags' lists and shard into the options; false with *why naming the field.
bool FillOptions(BenchmarkFlags* flags, std::string* why) {
  BenchmarkOptions& options = flags->options;
  options.estimators.clear();
  for (const std::string& name : flags->estimators) {
    TorqueEstimator estimator{};
    if (!ParseListItem(name, kTorqueEstimatorNames, "estimators", &estimator, why)) return false;
    options.estimators.push_back(estimator);
  }
  options.presets.clear();
  for (const std::string& name : flags->presets) {
    NoisePreset preset{};
    if (!ParseListItem(name, kNoisePresetNames, "presets", &preset, why)) return false;
    options.presets.push_back(preset);
  }
  if (!flags->shard.empty()) {
    char rest = 0;
    if (std::sscanf(flags->shard.c_str(), "%d/%d%c", &options.shard_index, &options.shard_count, &rest) != 2) {
      *why = "shard: expected K/N (the K-th of N slices, K from 0), got '" + flags->shard + "'";
      return false;
    }
  }
  return true;
}

// A progress line on stderr: rewritten in place on a terminal, else one per tenth.
BenchmarkProgress ProgressLine() {
  const bool terminal = ::isatty(::fileno(stderr)) != 0;
  return [terminal](int done, int total) {
    if (terminal) {
      std::fprintf(stderr, "\rbenchmark: %d/%d trials%s", done, total, done == total ? "\n" : "");
    } else if (done == total || (10 * done) / total != (10 * (done - 1)) / total) {
      std::fprintf(stderr, "benchmark: %d/%d trials\n", done, total);
    }
    std::fflush(stderr);
  };
}

void WriteBenchmark(const BenchmarkResult& result, const std::string& out_dir) {
  const std::filesystem::path dir(out_dir);
  EnsureOutputDirectory(dir);
  WriteFileAtomically(dir / "benchmark.json", FormatBenchmarkJson(result));
  WriteFileAtomically(dir / "parameter_errors.png", RenderPlot(BenchmarkErrorPlot(result), PlotFormat::kPng));
  std::printf("wrote %s and parameter_errors.png\n", (dir / "benchmark.json").c_str());
}

int BenchmarkCommand(BenchmarkFlags* flags, const UrdfLoadOptions& load, const CliContext& context) {
  std::string why;
  if (!FillOptions(flags, &why) || !flags->options.IsValid(&why)) return context.UsageError(why);
  const RobotModel model = LoadRobotOrThrow(flags->options.robot, load);
  const BenchmarkResult result = RunBenchmark(model, flags->options, ProgressLine());
  std::fputs(FormatBenchmarkTable(result).c_str(), stdout);
  WriteBenchmark(result, flags->options.out_dir);
  return 0;
}

int MergeCommand(const BenchmarkFlags& flags, const CliContext& context) {
  if (flags.merge_dirs.empty()) return context.UsageError("merge: expected the directories of the shards");
  if (flags.merge_dirs.size() > static_cast<size_t>(BenchmarkOptions::kMaxShards)) {
    return context.UsageError("merge: expected at most " + std::to_string(BenchmarkOptions::kMaxShards) +
                              " directories, got " + std::to_string(flags.merge_dirs.size()));
  }
  if (std::string why; !IsUsableOutputDirectory(flags.merge_out, "out_dir", &why)) return context.UsageError(why);
  std::vector<BenchmarkResult> parts;
  std::vector<std::string> sources;
  for (const std::string& dir : flags.merge_dirs) {
    sources.push_back((std::filesystem::path(dir) / "benchmark.json").string());
    parts.push_back(ParseBenchmarkJson(ReadInputFile(sources.back()), sources.back()));
  }
  const BenchmarkResult merged = MergeBenchmarkResults(parts, sources);
  std::fputs(FormatBenchmarkTable(merged).c_str(), stdout);
  WriteBenchmark(merged, flags.merge_out);
  return 0;
}

}  // namespace

CliCommand AddBenchmarkCommand(CLI::App* app, CliContext* context) {
  context->AddSpellings(kBenchmarkSpellings);
  auto flags = std::make_shared<BenchmarkFlags>();
  BenchmarkOptions& options = flags->options;
  CLI::App* command = app->add_subcommand(
      "benchmark", "Monte-Carlo benchmark of the estimators on closed-loop simulations under noise presets");
  AddRobotFlags(command, &options.robot, context->robot_load());
  command->add_option("--trajectory", options.trajectory,
                      "Reference the controller tracks: built-in motion (10 s) or trajectory file (.json, .csv)")
      ->capture_default_str();
  command->add_option("--controller", options.controller,
                      "Controller file {\"kp\": [...], \"kd\": [...], \"ki\": [...], \"tau_max\": [...], "
                      "\"feedforward\": \"model\"} (required)");
  command->add_option("--estimators", flags->estimators, "Estimators to rank: ols, wls, pc, tls, irls, iv, didim")
      ->delimiter(',')
      ->capture_default_str();
  AddFrictionFlag(command, &options.friction, "Friction terms identified (the truth: the robot file's)");
  command->add_option("--trials", options.trials, "Trials per noise preset")->capture_default_str();
  command->add_option("--preset", flags->presets,
                      "Noise presets (BIRDy's): none, low (1e-4 deg, 0.05 N m), high (1e-2 deg, 0.10 N m); "
                      "repeat or comma-separate for several")
      ->delimiter(',')
      ->capture_default_str();
  AddSeedFlag(command, &options.seed, "Seed: each trial's noise from (seed, preset, trial)");
  command->add_option("--threads", options.threads, "Trials run at once; 0: one per core")->capture_default_str();
  command->add_option("--shard", flags->shard,
                      "Run only the K-th (from 0) of N disjoint slices of the trials, e.g. 0/4; join them with "
                      "`benchmark merge`");
  AddOutFlag(command, &options.out_dir, "Directory for benchmark.json and parameter_errors.png")->capture_default_str();

  CLI::App* merge = command->add_subcommand(
      "merge", "Join the benchmark.json of the shards of one run into the single run's (bit for bit)");
  merge->add_option("dirs", flags->merge_dirs, "The shards' output directories")->required();
  AddOutFlag(merge, &flags->merge_out, "Directory for the merged benchmark.json and parameter_errors.png")->required();

  return {command, [flags, merge, context] {
            if (merge->parsed()) return MergeCommand(*flags, *context);
            return BenchmarkCommand(flags.get(), *context->robot_load(), *context);
          }};
}

}  // namespace idbench::cli
