#include "idbench/workbench/formats/atomic_file.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace idbench {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_atomic_file_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string Slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  int Entries() const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, ReplacesAFileKeepingItsMode) {
  const fs::path file = dir_ / "a.txt";
  std::ofstream(file) << "old";
  ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
  WriteFileAtomically(file, "new");
  EXPECT_EQ(Slurp(file), "new");
  struct stat status;
  ASSERT_EQ(::stat(file.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 0640u);
  EXPECT_EQ(Entries(), 1);  // no temporary file left
}

TEST_F(AtomicFileTest, FollowsASymlinkToItsFileAndKeepsTheLink) {
  fs::create_directories(dir_ / "elsewhere");
  const fs::path target = dir_ / "elsewhere" / "t.txt", link = dir_ / "link.txt";
  std::ofstream(target) << "old";
  fs::create_symlink(target, link);
  WriteFileAtomically(link, "new");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Slurp(target), "new");
  EXPECT_EQ(Entries(), 2);
}

// A device, FIFO, directory or dangling link is refused and left as it is;
// in a set, no file is written when one target is refused.
TEST_F(AtomicFileTest, RefusesWhatIsNotARegularFileAndWritesNothing) {
  const fs::path fifo = dir_ / "fifo", kept = dir_ / "kept.txt";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::ofstream(kept) << "mine";
  fs::create_symlink(dir_ / "missing" / "x", dir_ / "dangling");
  fs::create_symlink(fifo, dir_ / "to_fifo");
  const auto refusal = [](const fs::path& path) -> std::string {
    try {
      WriteFilesAtomically({{path.parent_path() / "kept.txt", "changed"}, {path, "x"}});
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refusal(fifo), "'" + fifo.string() + "' is a FIFO (named pipe), not a regular file; give a file name");
  EXPECT_EQ(refusal(dir_ / "to_fifo"), "'" + (dir_ / "to_fifo").string() +
                                            "' is a symbolic link to a FIFO (named pipe), not a regular file; give a "
                                            "file name");
  EXPECT_EQ(refusal(dir_), "'" + dir_.string() + "' is a directory, not a regular file; give a file name");
  EXPECT_EQ(refusal(dir_ / "dangling"), "'" + (dir_ / "dangling").string() + "' is a symbolic link to '" +
                                            (dir_ / "missing" / "x").string() +
                                            "', which does not exist; remove the link or give another file name");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(Slurp(kept), "mine");
  EXPECT_EQ(Entries(), 4);  // fifo, kept.txt, dangling, to_fifo: no temporary file
  std::string why;
  EXPECT_FALSE(IsUsableOutputFile("/dev/null", "--out", &why));
  EXPECT_EQ(why, "--out: '/dev/null' is a character device, not a regular file; give a file name");
  EXPECT_TRUE(IsUsableOutputFile((dir_ / "new.png").string(), "--out", &why));
  EXPECT_FALSE(IsUsableOutputDirectory(kept.string(), "--out", &why));
  EXPECT_EQ(why, "--out: '" + kept.string() + "' exists and is not a directory");
}

// An output directory that create_directories could not make is refused
// by the option check, before any work (6ab1a0b let a dangling symbolic link
// pass and failed after the work): the link itself, the link as a parent, a
// file as a parent; a new directory under an existing one is fine.
TEST_F(AtomicFileTest, OutputDirectoryThroughADanglingLinkIsRefusedUpFront) {
  fs::create_symlink(dir_ / "nowhere", dir_ / "dangling");
  std::ofstream(dir_ / "file.txt") << "x";
  std::string why;
  EXPECT_FALSE(IsUsableOutputDirectory((dir_ / "dangling").string(), "--out", &why));
  EXPECT_EQ(why, "--out: '" + (dir_ / "dangling").string() + "' is a symbolic link to '" + (dir_ / "nowhere").string() +
                     "', which does not exist");
  EXPECT_FALSE(IsUsableOutputDirectory((dir_ / "dangling" / "sub").string(), "--out", &why));
  EXPECT_NE(why.find("'" + (dir_ / "dangling").string() + "' is a symbolic link"), std::string::npos) << why;
  EXPECT_FALSE(IsUsableOutputDirectory((dir_ / "file.txt" / "sub").string(), "--out", &why));
  EXPECT_EQ(why, "--out: '" + (dir_ / "file.txt").string() + "' exists and is not a directory");
  EXPECT_TRUE(IsUsableOutputDirectory((dir_ / "new" / "deeper").string(), "--out", &why));
  fs::create_directories(dir_ / "real");
  fs::create_symlink(dir_ / "real", dir_ / "link");
  EXPECT_TRUE(IsUsableOutputDirectory((dir_ / "link").string(), "--out", &why));
}

}  // namespace
}  // namespace idbench
