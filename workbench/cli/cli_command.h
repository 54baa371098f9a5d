// What every subcommand of the `idbench` command line shares: the exit codes,
// the context the subcommands are added with (the command line as typed, the
// field → flag spellings of every command), and a subcommand once added (its
// CLI11 app, and how it runs once parsed). main.cc dispatches; each
// <command>_cli.cc declares one command's flags and runs it.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/urdf.h"
#include "idbench/workbench/commands/field_spelling.h"

namespace idbench::cli {

// One rule for every command (docs/exit-codes.md): 0 ok; kExitUsage the
// options or an input file are wrong (a usage error, or std::invalid_argument
// from reading or checking the inputs), nothing written; kExitFailure it ran
// and failed (any other error), nothing written.
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// Thrown for a usage error found after parsing; main() exits with kExitUsage.
struct UsageException : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// An option field as library messages name it (time_window) and the flag
// that sets it (--time-window). Each command keeps its table beside its flags.
using FieldFlag = FieldSpelling;

// The message with the fields every command shares (robot, locked_joints,
// out_dir, ...) spelled as their flags, as CliContext::FlagSpelling does.
std::string SharedFlagSpelling(const std::string& message);

// What the subcommands are added with; main() keeps it for as long as they run.
class CliContext {
 public:
  // Starts with the spellings of the fields every command shares (out_dir,
  // robot, friction, duration, ...).
  explicit CliContext(std::string command_line);

  // The command line as typed ("idbench identify --data log.csv"), recorded in the results.
  const std::string& command_line() const { return command_line_; }

  // What --lock and --tip say (AddRobotLoadFlags): one for the whole command
  // line, as CLI11 parses a line naming several subcommands (`idbench
  // simulate identify --lock ...`) and main() runs one of them with them all.
  UrdfLoadOptions* robot_load() { return &robot_load_; }

  // Adds a command's field → flag table. Every table applies to every
  // message: a message from reading a log names time_window for identify and
  // gains alike, and a parse error is spelled before any command runs.
  void AddSpellings(std::span<const FieldFlag> table);
  // The message with its fields spelled as their flags (SpellFields: a
  // plain word such as data only where it labels text or is quoted).
  std::string FlagSpelling(std::string message) const;

  // "idbench: error: MESSAGE" on stderr, flag-spelled; returns kExitUsage.
  int UsageError(const std::string& message) const;
  // One "idbench: warning: ..." line per warning on stderr, flag-spelled.
  void PrintWarnings(const std::vector<std::string>& warnings) const;

 private:
  std::string command_line_;
  UrdfLoadOptions robot_load_;
  std::vector<FieldFlag> spellings_;
};

// A subcommand with its flags declared. Once `app` was parsed, run() runs the
// command and returns its exit code; it throws what main() maps to one
// (std::invalid_argument: kExitUsage; any other exception: kExitFailure).
struct CliCommand {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

// Each adds its subcommand to `app` (<command>_cli.cc), its flags filling the
// command's options struct; `context` must outlive the returned command.
CliCommand AddRunCommand(CLI::App* app, CliContext* context);
CliCommand AddSimulateCommand(CLI::App* app, CliContext* context);
CliCommand AddIdentifyCommand(CLI::App* app, CliContext* context);
CliCommand AddGainsCommand(CLI::App* app, CliContext* context);
CliCommand AddPayloadCommand(CLI::App* app, CliContext* context);
CliCommand AddMonteCarloCommand(CLI::App* app, CliContext* context);
CliCommand AddBenchmarkCommand(CLI::App* app, CliContext* context);
CliCommand AddRenderCommand(CLI::App* app, CliContext* context);
CliCommand AddDesignCommand(CLI::App* app, CliContext* context);
CliCommand AddCompareCommand(CLI::App* app, CliContext* context);
CliCommand AddReportCommand(CLI::App* app, CliContext* context);
CliCommand AddExportCommand(CLI::App* app, CliContext* context);
CliCommand AddGuiCommand(CLI::App* app, CliContext* context);

// The `idbench` command line (idbench_app.cc): sets up `app` (description,
// --version) and adds every subcommand, in the order `idbench --help` lists
// them (main() decides which runs when a line names several). The CLI and
// the flag reference (flag_reference.h) both build it here. Does not name
// `app`: the CLI's is named by argv[0] when parsed.
std::vector<CliCommand> AddIdbenchCommands(CLI::App* app, CliContext* context);

}  // namespace idbench::cli
