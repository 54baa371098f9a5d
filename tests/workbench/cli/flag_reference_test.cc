// The flag reference docs/flags/ (workbench/cli/flag_reference.h) against the
// command line: regenerated into a temporary directory it must equal the
// committed files, and each page must list the flags `idbench <command> --help`
// lists (CLI11's own help, the independent account of the same flags).
#include <gtest/gtest.h>

#include "workbench/cli/cli_fixture.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using idbench::testing::Result;
using idbench::testing::Slurp;

const fs::path kDocs = fs::path(IDBENCH_SOURCE_DIR) / "docs" / "flags";
constexpr const char* kRegenerate = "regenerate with `cmake --build build --target idbench_flag_docs`";

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A line diff (longest common subsequence): "-N: committed line", "+N: generated line".
std::string LineDiff(const std::string& committed, const std::string& generated) {
  const std::vector<std::string> a = Lines(committed), b = Lines(generated);
  std::vector<std::vector<int>> common(a.size() + 1, std::vector<int>(b.size() + 1, 0));
  for (size_t i = a.size(); i-- > 0;)
    for (size_t j = b.size(); j-- > 0;)
      common[i][j] = a[i] == b[j] ? common[i + 1][j + 1] + 1 : std::max(common[i + 1][j], common[i][j + 1]);
  std::ostringstream diff;
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (i < a.size() && j < b.size() && a[i] == b[j]) {
      ++i, ++j;
    } else if (i < a.size() && (j == b.size() || common[i + 1][j] >= common[i][j + 1])) {
      diff << "-" << i + 1 << ": " << a[i] << "\n";
      ++i;
    } else {
      diff << "+" << j + 1 << ": " << b[j] << "\n";
      ++j;
    }
  }
  return diff.str();
}

std::set<std::string> MarkdownFiles(const fs::path& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".md") names.insert(entry.path().filename().string());
  return names;
}

class FlagReferenceTest : public idbench::testing::CliFixture {};

TEST_F(FlagReferenceTest, CommittedReferenceIsWhatTheFlagTablesGenerate) {
  const fs::path generated = dir_ / "flags";
  const std::string command = std::string(IDBENCH_FLAG_REFERENCE) + " " + generated.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::set<std::string> committed_files = MarkdownFiles(kDocs), generated_files = MarkdownFiles(generated);
  EXPECT_GE(generated_files.size(), 11u);  // README.md and ten commands
  for (const std::string& name : generated_files) {
    EXPECT_TRUE(committed_files.count(name)) << "docs/flags/" << name << " is missing; " << kRegenerate;
  }
  for (const std::string& name : committed_files) {
    if (!generated_files.count(name)) {
      ADD_FAILURE() << "docs/flags/" << name << " documents no command any more: delete it";
      continue;
    }
    const std::string committed = Slurp(kDocs / name), fresh = Slurp(generated / name);
    EXPECT_EQ(committed, fresh) << "docs/flags/" << name << " differs from the command line's flags ("
                                << kRegenerate << "):\n" << LineDiff(committed, fresh);
  }
}

// The long flags at the start of option lines: "  --motion,--trajectory TEXT ..."
// in --help, "| `--motion`, `--trajectory` | ..." in a reference page.
std::set<std::string> LongFlags(const std::string& text, const std::regex& line_start) {
  std::set<std::string> flags;
  const std::regex flag("--[a-z0-9-]+");
  for (const std::string& line : Lines(text)) {
    std::smatch start;
    if (!std::regex_search(line, start, line_start)) continue;
    const std::string names = start.str(0);
    for (std::sregex_iterator it(names.begin(), names.end(), flag), end; it != end; ++it) flags.insert(it->str());
  }
  return flags;
}

TEST_F(FlagReferenceTest, EachPageListsTheFlagsOfItsCommandsHelp) {
  const std::regex help_names("^  -[^ ]*");         // "  --robot TEXT=...": the names before the first space
  const std::regex page_names("^\\| `-[^|]*");      // "| `--robot` | ...": the first cell
  int commands = 0;
  for (const std::string& page : MarkdownFiles(kDocs)) {
    if (page == "README.md") continue;
    const std::string command = fs::path(page).stem().string();
    const Result help = Run(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << ": " << help.err;
    std::set<std::string> expected = LongFlags(help.out, help_names);
    expected.erase("--help");
    const std::set<std::string> documented = LongFlags(Slurp(kDocs / page), page_names);
    EXPECT_FALSE(documented.empty()) << page;
    EXPECT_EQ(documented, expected) << "docs/flags/" << page << " against `idbench " << command << " --help`";
    ++commands;
  }
  EXPECT_EQ(commands, 13);
}

}  // namespace
