#include "cli_command.h"

#include <cstdio>

namespace idbench::cli {

namespace {

// Fields several commands' options share, one flag each.
constexpr FieldFlag kSharedSpellings[] = {{"out_dir", "--out"},     {"robot", "--robot"},
                                          {"friction", "--friction"}, {"coulomb_smoothing", "--coulomb-smoothing"},
                                          {"duration", "--duration"}, {"dt", "--dt"}};

}  // namespace

CliContext::CliContext(std::string command_line) : command_line_(std::move(command_line)) {
  AddSpellings(kSharedSpellings);
}

void CliContext::AddSpellings(std::span<const FieldFlag> table) {
  spellings_.insert(spellings_.end(), table.begin(), table.end());
}

std::string CliContext::FlagSpelling(std::string message) const {
  for (const auto& [field, flag] : spellings_) {
    const std::string f(field);
    for (size_t at = message.find(f); at != std::string::npos; at = message.find(f, at + 1)) {
      // A word of its own (not part of a path such as /tmp/time_window.csv).
      // A field that is a plain word (data, topic) only where it cannot be
      // English: as a label, "data: ..." at the start, after ": " or "(".
      const size_t end = at + f.size();
      bool word = (at == 0 || std::string(" (,").find(message[at - 1]) != std::string::npos) &&
                  (end == message.size() || std::string(" :,);").find(message[end]) != std::string::npos);
      if (word && f.find('_') == std::string::npos) {
        const bool label = end < message.size() && message[end] == ':' &&
                           (at == 0 || message[at - 1] == '(' || (at >= 2 && message.compare(at - 2, 2, ": ") == 0));
        word = label;
      }
      if (word) message.replace(at, f.size(), flag);
    }
  }
  return message;
}

int CliContext::UsageError(const std::string& message) const {
  std::fprintf(stderr, "idbench: error: %s\n", FlagSpelling(message).c_str());
  return kExitUsage;
}

void CliContext::PrintWarnings(const std::vector<std::string>& warnings) const {
  for (const std::string& w : warnings) std::fprintf(stderr, "idbench: warning: %s\n", FlagSpelling(w).c_str());
}

}  // namespace idbench::cli
