#include "idbench/engine/input_file.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace idbench {
namespace {

namespace fs = std::filesystem;

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_input_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    ::unsetenv("IDBENCH_MAX_INPUT_MB");
    fs::remove_all(dir_);
  }
  // The message `ReadInputFile(path)` throws (empty if it does not).
  static std::string Refusal(const std::string& path) {
    try {
      ReadInputFile(path);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(InputFileTest, ReadsARegularFileWholeAndThroughASymlink) {
  const std::string text = std::string("a\0b\nline two", 12);
  std::ofstream(dir_ / "f.txt", std::ios::binary) << text;
  EXPECT_EQ(ReadInputFile((dir_ / "f.txt").string()), text);
  fs::create_symlink(dir_ / "f.txt", dir_ / "link.txt");
  EXPECT_EQ(ReadInputFile((dir_ / "link.txt").string()), text);
}

// A FIFO is refused at once (reading it would wait for a writer: a hang,
// under the CTest timeout), and so are devices and directories.
TEST_F(InputFileTest, RefusesWhatIsNotARegularFileSayingWhatItIs) {
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(Refusal(fifo.string()), fifo.string() + ": is a FIFO (named pipe), not a regular file; pass a file");
  EXPECT_EQ(Refusal("/dev/zero"), "/dev/zero: is a character device, not a regular file; pass a file");
  EXPECT_EQ(Refusal(dir_.string()), dir_.string() + ": is a directory, not a regular file; pass a file");
  EXPECT_EQ(Refusal((dir_ / "missing").string()).rfind((dir_ / "missing").string() + ": cannot read the file (No such file", 0), 0u);
}

// The limit is 1/16 of physical memory, or IDBENCH_MAX_INPUT_MB; a sparse
// 3 MB file (nothing on disk) is refused under a 2 MB limit before it is read.
TEST_F(InputFileTest, RefusesFilesOverTheLimitNamingItAndHowToRaiseIt) {
  const std::uint64_t memory = static_cast<std::uint64_t>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGESIZE);
  EXPECT_EQ(MaxInputFileBytes(), memory / 16);
  const fs::path big = dir_ / "sparse.bin";
  std::ofstream(big).close();
  fs::resize_file(big, 3 * 1024 * 1024);
  EXPECT_EQ(ReadInputFile(big.string()).size(), 3u * 1024 * 1024);
  ::setenv("IDBENCH_MAX_INPUT_MB", "2", 1);
  EXPECT_EQ(MaxInputFileBytes(), 2u * 1024 * 1024);
  EXPECT_EQ(Refusal(big.string()), big.string() +
                                       ": the file is 3 MB, larger than the limit for input files, 2 MB "
                                       "(IDBENCH_MAX_INPUT_MB sets it; IDBENCH_MAX_INPUT_MB=N raises it to N MB)");
  // Not a positive integer: the default applies.
  ::setenv("IDBENCH_MAX_INPUT_MB", "-1", 1);
  EXPECT_EQ(MaxInputFileBytes(), memory / 16);
}

// Lines: 64 KiB by default (1024 columns of 64 characters), or
// IDBENCH_MAX_LINE_KB; the first line over it is named.
TEST_F(InputFileTest, LinesOverTheLimitAreNamedWithTheLimit) {
  EXPECT_EQ(MaxLineBytes(), 65536u);
  const std::string text = "short\n" + std::string(65536, 'x') + "\n" + std::string(65537, 'y') + "\n";
  try {
    CheckLineLengths(text, "f.csv");
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "f.csv:3: the line is 65537 bytes, longer than the limit for a line, 64 KB (1024 columns "
                           "of 64 characters; IDBENCH_MAX_LINE_KB=N raises it to N KB)");
  }
  ::setenv("IDBENCH_MAX_LINE_KB", "128", 1);
  EXPECT_EQ(MaxLineBytes(), 131072u);
  CheckLineLengths(text, "f.csv");
  ::unsetenv("IDBENCH_MAX_LINE_KB");
}

}  // namespace
}  // namespace idbench
