#include "idbench/engine/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace idbench {
namespace {

constexpr std::uint64_t kMegabyte = 1024 * 1024;
constexpr const char* kVariable = "IDBENCH_MAX_INPUT_MB";

// The value of IDBENCH_MAX_INPUT_MB in bytes; 0 when unset or not a positive integer.
std::uint64_t LimitFromEnvironment() {
  const char* text = std::getenv(kVariable);
  if (text == nullptr || *text == '\0') return 0;
  char* end = nullptr;
  errno = 0;
  const unsigned long long megabytes = std::strtoull(text, &end, 10);
  if (errno != 0 || *end != '\0' || megabytes == 0 || megabytes > UINT64_MAX / kMegabyte) return 0;
  return megabytes * kMegabyte;
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
  if (::stat(path.c_str(), &status) != 0) FailErrno(path, "cannot open the file for reading");
  CheckStatus(path, status);
}

std::string ReadInputFile(const std::string& path) {
  CheckInputFile(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) FailErrno(path, "cannot open the file for reading");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat status;
  if (::fstat(fd, &status) != 0) FailErrno(path, "cannot open the file for reading");
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

}  // namespace idbench
