#include "idbench/workbench/formats/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

namespace idbench {

void EnsureOutputDirectory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw std::runtime_error("output path '" + dir.string() + "' exists and is not a directory");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create output directory '" + dir.string() + "': " + ec.message());
}

namespace {

namespace fs = std::filesystem;

// What an existing path that is not a regular file is, for a message.
std::string KindOf(const struct stat& status) {
  if (S_ISDIR(status.st_mode)) return "a directory";
  if (S_ISCHR(status.st_mode)) return "a character device";
  if (S_ISBLK(status.st_mode)) return "a block device";
  if (S_ISFIFO(status.st_mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(status.st_mode)) return "a socket";
  return "not a regular file";
}

// The file an output path writes to, with its status when it exists. Throws
// std::runtime_error "'PATH' is ..." for what may not be replaced.
struct Target {
  fs::path path;                      // `path`, or the regular file its links lead to
  std::optional<struct stat> status;  // of that file, when it exists
};
Target OutputTarget(const fs::path& path) {
  struct stat link_status;
  if (::lstat(path.c_str(), &link_status) != 0) return {path, std::nullopt};  // missing: created
  struct stat status;
  const bool is_link = S_ISLNK(link_status.st_mode);
  if (::stat(path.c_str(), &status) != 0) {
    throw std::runtime_error("'" + path.string() + "' is a symbolic link to '" +
                             fs::read_symlink(path).string() +
                             "', which does not exist; remove the link or give another file name");
  }
  if (!S_ISREG(status.st_mode)) {
    throw std::runtime_error("'" + path.string() + "' is " + (is_link ? "a symbolic link to " : "") +
                             KindOf(status) + ", not a regular file; give a file name");
  }
  if (!is_link) return {path, status};
  std::error_code ec;
  const fs::path resolved = fs::canonical(path, ec);
  if (ec) throw std::runtime_error("cannot follow the symbolic link '" + path.string() + "': " + ec.message());
  return {resolved, status};
}

// A new temporary file next to `target` (same file system, so the rename is
// atomic), opened for writing; its path in *temp.
int CreateTemp(const fs::path& target, fs::path* temp) {
  for (int attempt = 0;; ++attempt) {
    *temp = target.parent_path() / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                                    (attempt > 0 ? "-" + std::to_string(attempt) : ""));
    const int fd = ::open(temp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST || attempt >= 100) return fd;
  }
}

// Writes and syncs `content` to a temporary file for `target`, with the
// existing file's permission bits (and owner, when root); its path in *temp.
// Throws naming `path` (what the user gave) on failure.
void WriteTemp(const Target& target, const fs::path& path, std::string_view content, fs::path* temp) {
  const auto fail = [&](const std::string& reason) {
    throw std::runtime_error("cannot write '" + path.string() + "': " + reason);
  };
  const int fd = CreateTemp(target.path, temp);
  if (fd < 0) fail(std::strerror(errno));
  bool ok = true;
  if (target.status) {
    ok = ::fchmod(fd, target.status->st_mode & 07777) == 0;
    if (ok && ::geteuid() == 0) (void)!::fchown(fd, target.status->st_uid, target.status->st_gid);
  }
  for (size_t done = 0; ok && done < content.size();) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += static_cast<size_t>(n);
  }
  ok = ok && ::fsync(fd) == 0;
  const std::string reason = std::strerror(errno);
  ok = (::close(fd) == 0) && ok;
  if (!ok) {
    std::remove(temp->c_str());
    fail(reason);
  }
}

// Why `path` cannot be an output file (empty if it can).
std::string OutputFileProblem(const std::string& path) {
  try {
    OutputTarget(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

bool IsUsableOutputDirectory(const std::string& dir, const std::string& option, std::string* why) {
  std::string problem;
  std::error_code ec;
  if (dir.empty()) problem = "empty path";
  else if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) problem = "'" + dir + "' exists and is not a directory";
  // What create_directories would meet, checked before any work: a path (or
  // a parent) that is a symbolic link to nothing, a parent that is not a
  // directory, a nearest existing parent that cannot be written.
  for (fs::path p = fs::path(dir); problem.empty() && !p.empty(); p = p.parent_path()) {
    if (fs::is_symlink(p, ec) && !fs::exists(p, ec)) {
      problem = "'" + p.string() + "' is a symbolic link to '" + fs::read_symlink(p, ec).string() +
                "', which does not exist";
    } else if (fs::exists(p, ec)) {
      if (!fs::is_directory(p, ec)) problem = "'" + p.string() + "' exists and is not a directory";
      else if (::access(p.c_str(), W_OK | X_OK) != 0) problem = "'" + p.string() + "' cannot be written: " + std::strerror(errno);
      break;
    }
    if (p == p.parent_path()) break;
  }
  if (problem.empty()) return true;
  if (why) *why = option + ": " + problem;
  return false;
}

bool IsUsableOutputFile(const std::string& path, const std::string& option, std::string* why) {
  const std::string problem = path.empty() ? "empty path" : OutputFileProblem(path);
  if (problem.empty()) return true;
  if (why) *why = option + ": " + problem;
  return false;
}

void WriteFilesAtomically(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<Target> targets;
  for (const auto& [path, content] : files) targets.push_back(OutputTarget(path));
  std::vector<fs::path> temps;
  try {
    for (size_t k = 0; k < files.size(); ++k) {
      fs::path temp;
      WriteTemp(targets[k], files[k].first, files[k].second, &temp);
      temps.push_back(temp);
    }
  } catch (...) {
    for (const auto& tmp : temps) std::remove(tmp.c_str());
    throw;
  }
  for (size_t k = 0; k < files.size(); ++k) {
    if (std::rename(temps[k].c_str(), targets[k].path.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      for (size_t r = k; r < temps.size(); ++r) std::remove(temps[r].c_str());
      throw std::runtime_error("cannot write '" + files[k].first.string() + "': " + reason);
    }
  }
}

void WriteFileAtomically(const fs::path& path, std::string_view content) {
  WriteFilesAtomically({{path, std::string(content)}});
}

}  // namespace idbench
