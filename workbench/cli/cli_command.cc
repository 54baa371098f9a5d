#include "cli_command.h"

#include <cstdio>

namespace idbench::cli {

void CliContext::AddSpellings(std::span<const FieldFlag> table) {
  spellings_.insert(spellings_.end(), table.begin(), table.end());
}

std::string CliContext::FlagSpelling(std::string message) const {
  for (const auto& [field, flag] : spellings_) {
    const std::string f(field);
    for (size_t at = message.find(f); at != std::string::npos; at = message.find(f, at + 1)) {
      // A word of its own (not part of a path such as /tmp/time_window.csv).
      const std::string before = " (,", after = " :,);";
      const bool word = (at == 0 || before.find(message[at - 1]) != std::string::npos) &&
                        (at + f.size() == message.size() || after.find(message[at + f.size()]) != std::string::npos);
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
