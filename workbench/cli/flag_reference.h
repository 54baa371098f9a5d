// The flag reference (docs/flags/): each command's flags as Markdown, read
// from the same CLI11 apps the command line parses with (idbench_app.cc), so
// that it says what `idbench <command> --help` says and cannot drift.
// Regenerate after changing a flag:
//   cmake --build build --target idbench_flag_docs
// (runs `idbench_flag_reference docs/flags`); tests/workbench/cli/
// flag_reference_test.cc fails while docs/flags/ differs from what it writes.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

namespace idbench::cli {

// {file name, Markdown}: README.md (the commands, one line each) and
// <command>.md per subcommand of `app` (a table: flag, value, default,
// description), in the order of the subcommands.
std::vector<std::pair<std::string, std::string>> FlagReferenceFiles(const CLI::App& app);

}  // namespace idbench::cli
