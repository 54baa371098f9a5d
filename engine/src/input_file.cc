#include "idbench/engine/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace idbench {
namespace {

constexpr std::uint64_t kMegabyte = 1024 * 1024;
constexpr const char* kVariable = "IDBENCH_MAX_INPUT_MB";

constexpr const char* kLineVariable = "IDBENCH_MAX_LINE_KB";

// The value of an environment variable times `unit` [bytes]; 0 when unset or
// not a positive integer.
std::uint64_t LimitFromEnvironment(const char* variable = kVariable, std::uint64_t unit = kMegabyte) {
  const char* text = std::getenv(variable);
  if (text == nullptr || *text == '\0') return 0;
  char* end = nullptr;
  errno = 0;
  const unsigned long long count = std::strtoull(text, &end, 10);
  if (errno != 0 || *end != '\0' || count == 0 || count > UINT64_MAX / unit) return 0;
  return count * unit;
}

// What a file that is not regular is, for a message.
const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Refuses what `status` (of `path`) says cannot be read as an input file.
void CheckStatus(const std::string& path, const struct stat& status) {
  if (!S_ISREG(status.st_mode)) {
    throw std::invalid_argument(path + ": is " + KindOf(status.st_mode) + ", not a regular file; pass a file");
  }
  const std::uint64_t size = static_cast<std::uint64_t>(status.st_size);
  if (size > MaxInputFileBytes()) {
    throw std::invalid_argument(path + ": the file is " + std::to_string(size / kMegabyte) +
                                " MB, larger than the limit for input files, " + InputLimitDescription());
  }
}

[[noreturn]] void FailErrno(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

std::uint64_t MaxInputFileBytes() {
  if (const std::uint64_t bytes = LimitFromEnvironment(); bytes > 0) return bytes;
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return 256 * kMegabyte;  // unknown memory: a small machine's share
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) / 16;
}

std::string InputLimitDescription() {
  const bool from_environment = LimitFromEnvironment() > 0;
  return std::to_string(MaxInputFileBytes() / kMegabyte) + " MB (" +
         (from_environment ? std::string(kVariable) + " sets it" : "1/16 of this machine's memory") + "; " +
         kVariable + "=N raises it to N MB)";
}

void CheckInputFile(const std::string& path) {
  struct stat status;
  if (::stat(path.c_str(), &status) != 0) FailErrno(path, "cannot read the file");
  CheckStatus(path, status);
}

bool IsSameFile(const std::string& a, const std::string& b) {
  if (a == b) return true;
  // Device and inode, as std::filesystem::equivalent compares them.
  struct stat status_a, status_b;
  if (::stat(a.c_str(), &status_a) != 0 || ::stat(b.c_str(), &status_b) != 0) return false;
  return status_a.st_dev == status_b.st_dev && status_a.st_ino == status_b.st_ino;
}

std::string ReadInputFile(const std::string& path) {
  CheckInputFile(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) FailErrno(path, "cannot read the file");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat status;
  if (::fstat(fd, &status) != 0) FailErrno(path, "cannot read the file");
  CheckStatus(path, status);
  // Read up to one byte past the limit: a file that grew after fstat is caught.
  std::string text;
  const std::uint64_t limit = MaxInputFileBytes();
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) FailErrno(path, "error while reading the file");
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > limit) {
      throw std::invalid_argument(path + ": the file grew beyond the limit for input files, " +
                                  InputLimitDescription());
    }
  }
  return text;
}

int OpenStreamedInputFile(const std::string& path) {
  struct stat status;
  if (::stat(path.c_str(), &status) != 0) FailErrno(path, "cannot read the file");
  if (!S_ISREG(status.st_mode)) CheckInputFile(path);  // throws, saying what it is
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) FailErrno(path, "cannot read the file");
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd);
    CheckInputFile(path);
    throw std::invalid_argument(path + ": is not a regular file; pass a file");  // replaced while opened
  }
  return fd;
}

std::size_t MaxLineBytes() {
  const std::uint64_t bytes = LimitFromEnvironment(kLineVariable, 1024);
  return bytes > 0 ? static_cast<std::size_t>(bytes) : 64 * 1024;
}

void CheckLineLengths(std::string_view text, const std::string& source) {
  const std::size_t limit = MaxLineBytes();
  int line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end - start > limit) {
      throw std::invalid_argument(source + ":" + std::to_string(line) + ": the line is " +
                                  std::to_string(end - start) + " bytes, longer than the limit for a line, " +
                                  std::to_string(limit / 1024) + " KB (" +
                                  (LimitFromEnvironment(kLineVariable, 1024) > 0
                                       ? std::string(kLineVariable) + " sets it"
                                       : std::string("1024 columns of 64 characters")) +
                                  "; " + kLineVariable + "=N raises it to N KB)");
    }
    start = end + 1;
  }
}

}  // namespace idbench
