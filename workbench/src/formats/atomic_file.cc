#include "idbench/workbench/formats/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
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

std::filesystem::path TempPath(const std::filesystem::path& path) {
  return path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()));
}

// Writes and flushes `content` to `tmp`; throws naming `path` on failure.
void WriteTemp(const std::filesystem::path& tmp, const std::filesystem::path& path, std::string_view content) {
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(errno));
  const bool written = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const bool synced = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !synced || !closed) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path.string() + "': " + reason);
  }
}

}  // namespace

void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files) {
  std::vector<std::filesystem::path> temps;
  try {
    for (const auto& [path, content] : files) {
      temps.push_back(TempPath(path));
      WriteTemp(temps.back(), path, content);
    }
  } catch (...) {
    for (const auto& tmp : temps) std::remove(tmp.c_str());
    throw;
  }
  for (size_t k = 0; k < files.size(); ++k) {
    if (std::rename(temps[k].c_str(), files[k].first.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      for (size_t r = k; r < temps.size(); ++r) std::remove(temps[r].c_str());
      throw std::runtime_error("cannot write '" + files[k].first.string() + "': " + reason);
    }
  }
}

void WriteFileAtomically(const std::filesystem::path& path, std::string_view content) {
  WriteFilesAtomically({{path, std::string(content)}});
}

}  // namespace idbench
