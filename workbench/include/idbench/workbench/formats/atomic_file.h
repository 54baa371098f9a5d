// Output files are written atomically: to a temporary file in the same
// directory, then renamed over the target, so a reader (or a crash) never sees
// a partial file and nothing else in the directory is touched.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace idbench {

// Creates `dir` (and parents) if missing. Throws std::runtime_error naming the
// path if it exists but is not a directory or cannot be created.
void EnsureOutputDirectory(const std::filesystem::path& dir);

// Writes several files as one unit: every temporary file is written first and
// only then are they renamed into place, so a failure leaves the previous set
// untouched. Throws std::runtime_error naming the path on failure.
void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

// Writes `content` to `path` atomically. Throws std::runtime_error naming the
// path on failure; the previous file, if any, is then left as it was.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace idbench
