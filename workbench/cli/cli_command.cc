#include "cli_command.h"

#include <cstdio>

namespace idbench::cli {

namespace {

// Fields several commands' options share, one flag each.
constexpr FieldFlag kSharedSpellings[] = {{"out_dir", "--out"},
                                          {"robot", "--robot"},
                                          {"locked_joints", "--lock"},
                                          {"tip_link", "--tip"},
                                          {"friction", "--friction"},
                                          {"coulomb_smoothing", "--coulomb-smoothing"},
                                          {"coulomb_min_speed", "--coulomb-min-speed"},
                                          {"duration", "--duration"},
                                          {"dt", "--dt"}};

}  // namespace

std::string SharedFlagSpelling(const std::string& message) { return SpellFields(message, kSharedSpellings); }

CliContext::CliContext(std::string command_line) : command_line_(std::move(command_line)) {
  AddSpellings(kSharedSpellings);
}

void CliContext::AddSpellings(std::span<const FieldFlag> table) {
  spellings_.insert(spellings_.end(), table.begin(), table.end());
}

std::string CliContext::FlagSpelling(std::string message) const { return SpellFields(std::move(message), spellings_); }

int CliContext::UsageError(const std::string& message) const {
  std::fprintf(stderr, "idbench: error: %s\n", FlagSpelling(message).c_str());
  return kExitUsage;
}

void CliContext::PrintWarnings(const std::vector<std::string>& warnings) const {
  for (const std::string& w : warnings) std::fprintf(stderr, "idbench: warning: %s\n", FlagSpelling(w).c_str());
}

}  // namespace idbench::cli
