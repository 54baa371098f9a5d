// The `idbench` command line as one CLI11 app: what `idbench --help` shows,
// --version, and every subcommand in the order listed there. Built here for
// the CLI (main.cc) and for the flag reference (flag_reference_main.cc).
#include <string>
#include <vector>

#include "cli_command.h"
#include "idbench/workbench/version.h"

namespace idbench::cli {

std::vector<CliCommand> AddIdbenchCommands(CLI::App* app, CliContext* context) {
  app->description("idbench: a workbench for robot excitation design and dynamic parameter identification");
  app->set_version_flag("--version", std::string("idbench ") + Version() + " (git " + GitRevision() + ")",
                        "Print the version and the git revision built from, then exit");
  return {AddRunCommand(app, context),        AddSimulateCommand(app, context), AddIdentifyCommand(app, context),
          AddGainsCommand(app, context),      AddPayloadCommand(app, context),  AddMonteCarloCommand(app, context),
          AddBenchmarkCommand(app, context),  AddRenderCommand(app, context),   AddDesignCommand(app, context),
          AddCompareCommand(app, context),    AddReportCommand(app, context),   AddExportCommand(app, context),
          AddGuiCommand(app, context)};
}

}  // namespace idbench::cli
