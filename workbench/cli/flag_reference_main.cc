// idbench_flag_reference DIR: writes the flag reference (flag_reference.h)
// of the `idbench` command line into DIR, as README.md and <command>.md.
// `cmake --build build --target idbench_flag_docs` runs it on docs/flags/.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_command.h"
#include "flag_reference.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: idbench_flag_reference DIR\n");
    return 2;
  }
  try {
    CLI::App app{"", "idbench"};
    idbench::cli::CliContext context("idbench");
    idbench::cli::AddIdbenchCommands(&app, &context);
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    for (const auto& [name, markdown] : idbench::cli::FlagReferenceFiles(app)) {
      std::ofstream out(dir / name, std::ios::binary);
      out << markdown;
      if (!out.flush()) throw std::runtime_error((dir / name).string() + ": cannot write");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench_flag_reference: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
