// idbench: design robot identification experiments, simulate them in Bullet,
// identify dynamic parameters. This file only dispatches: each subcommand's
// flags and run are in <command>_cli.cc (the list in idbench_app.cc). Exit
// codes, one rule for every command (docs/exit-codes.md): 0 ok; 2 the options
// or an input file are wrong (a usage error, or std::invalid_argument from
// reading or checking the inputs), nothing written; 1 it ran and failed (any
// other error), nothing written.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_command.h"

int main(int argc, char** argv) {
  using idbench::cli::CliCommand;
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(i ? argv[i] : "idbench");
  idbench::cli::CliContext context(command_line);
  CLI::App app;
  const std::vector<CliCommand> commands = idbench::cli::AddIdbenchCommands(&app, &context);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return context.UsageError(e.what());
  }

  // CLI11 parses a line naming several subcommands (`idbench design run`);
  // the first parsed in this order runs.
  const CliCommand* parsed = nullptr;
  for (const char* name : {"run", "simulate", "identify", "gains", "payload", "montecarlo", "benchmark", "render", "report",
                           "export", "design", "compare", "gui"}) {
    const auto command = std::find_if(commands.begin(), commands.end(),
                                      [name](const CliCommand& c) { return c.app->get_name() == name; });
    if (!parsed && command != commands.end() && command->app->parsed()) parsed = &*command;
  }
  try {
    if (parsed) return parsed->run();
  } catch (const std::invalid_argument& e) {  // also UsageException: the input is wrong
    return context.UsageError(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench: error: %s\n", context.FlagSpelling(e.what()).c_str());
    return idbench::cli::kExitFailure;
  }
  return context.UsageError("a subcommand is required (run, simulate, identify, gains, payload, montecarlo, benchmark, design, compare, render, report, export, gui); see idbench --help");
}
