#include "flag_reference.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace idbench::cli {
namespace {

constexpr const char* kGeneratedNote =
    "Generated from the command line's flag tables by `idbench_flag_reference` (workbench/cli/flag_reference.h); "
    "do not edit. Regenerate with `cmake --build build --target idbench_flag_docs`.";

// Text in a Markdown table cell: `|` would end the cell.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out;
}

// "`--motion`, `--trajectory`", or the positional's name.
std::string Names(const CLI::Option& option) {
  if (!option.nonpositional()) return "`" + option.get_name() + "`";
  std::string names;
  for (const std::string& name : option.get_snames()) names += (names.empty() ? "`-" : ", `-") + name + "`";
  for (const std::string& name : option.get_lnames()) names += (names.empty() ? "`--" : ", `--") + name + "`";
  return names;
}

// What follows the flag on the command line, as CLI11's help shows it:
// TYPE, "TYPE ..." (any number, repeated or comma-separated), "TYPE x N"; "" for a flag.
std::string Value(const CLI::Option& option) {
  if (option.get_type_size() == 0) return "";
  std::string value = option.get_type_name();
  if (option.get_expected_max() == CLI::detail::expected_max_vector_size) {
    value += " ...";
  } else if (option.get_expected_min() > 1) {
    value += " x " + std::to_string(option.get_expected());
  }
  return value;
}

// The default, "required", or "".
std::string Default(const CLI::Option& option) {
  if (option.get_required()) return "*required*";
  const std::string value = option.get_default_str();
  return value.empty() ? "" : "`" + value + "`";
}

// The description, with the flags it cannot be given with.
std::string Description(const CLI::Option& option) {
  std::string text = option.get_description();
  std::vector<std::string> excluded;
  for (const CLI::Option* other : option.get_excludes()) excluded.push_back(other->get_name());
  std::sort(excluded.begin(), excluded.end());
  for (const std::string& name : excluded) text += " (not with `" + name + "`)";
  return text;
}

// The table of a command's flags.
std::string FlagTable(const CLI::App& command) {
  std::ostringstream md;
  md << "| Flag | Value | Default | Description |\n"
     << "|---|---|---|---|\n";
  for (const CLI::Option* option : command.get_options()) {
    if (option == command.get_help_ptr()) continue;  // -h, --help: every command's
    md << "| " << Names(*option) << " | " << Cell(Value(*option)) << " | " << Cell(Default(*option)) << " | "
       << Cell(Description(*option)) << " |\n";
  }
  return md.str();
}

// A command's page: its flags, then each of its own subcommands' (`benchmark merge`).
std::string CommandPage(const std::string& program, const CLI::App& command) {
  std::ostringstream md;
  md << "# " << program << " " << command.get_name() << "\n\n"
     << command.get_description() << "\n\n"
     << kGeneratedNote << "\n\n"
     << FlagTable(command);
  for (const CLI::App* sub : command.get_subcommands({})) {
    md << "\n## " << program << " " << command.get_name() << " " << sub->get_name() << "\n\n"
       << sub->get_description() << "\n\n"
       << FlagTable(*sub);
  }
  return md.str();
}

std::string IndexPage(const std::string& program, const CLI::App& app) {
  std::ostringstream md;
  md << "# " << program << " command-line flags\n\n"
     << app.get_description() << "\n\n"
     << kGeneratedNote << "\n\n"
     << "| Command | What it does |\n"
     << "|---|---|\n";
  for (const CLI::App* command : app.get_subcommands({})) {
    md << "| [" << command->get_name() << "](" << command->get_name() << ".md) | "
       << Cell(command->get_description()) << " |\n";
  }
  md << "\nEvery command also takes `-h`, `--help`; `" << program
     << " --version` prints the version and the git revision built from.\n";
  return md.str();
}

}  // namespace

std::vector<std::pair<std::string, std::string>> FlagReferenceFiles(const CLI::App& app) {
  const std::string program = app.get_name();
  std::vector<std::pair<std::string, std::string>> files{{"README.md", IndexPage(program, app)}};
  for (const CLI::App* command : app.get_subcommands({})) {
    files.emplace_back(command->get_name() + ".md", CommandPage(program, *command));
  }
  return files;
}

}  // namespace idbench::cli
