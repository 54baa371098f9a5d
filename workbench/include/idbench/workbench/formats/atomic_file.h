// Output files are written atomically: to a temporary file in the same
// directory, then renamed over the target, so a reader (or a crash) never sees
// a partial file and nothing else in the directory is touched.
//
// What an output path may be (docs/exit-codes.md, "Output files"):
// - missing: it is created (mode 0666 less the umask);
// - a regular file: replaced; its permission bits (and, for root, its owner)
//   are kept;
// - a symbolic link: followed (through every link) to a regular file, which
//   is replaced in its own directory; the link stays. A link to nothing is
//   refused;
// - anything else (a directory, a device such as /dev/full, a FIFO, a
//   socket): refused, never replaced.
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

// Whether `dir` can be an output directory (for the options' IsValid): not
// empty, and missing or a directory (or a link to one). Else false with *why =
// "OPTION: 'DIR' exists and is not a directory" (or "OPTION: empty path").
bool IsUsableOutputDirectory(const std::string& dir, const std::string& option, std::string* why);

// Whether `path` can be an output file, as above: false with *why naming the
// option, the path and what it is ("OPTION: '/dev/full' is a character
// device, not a regular file; give a file name").
bool IsUsableOutputFile(const std::string& path, const std::string& option, std::string* why);

// Writes several files as one unit: every target is checked first, then every
// temporary file is written, and only then are they renamed into place, so a
// failure leaves the previous set untouched. Throws std::runtime_error naming
// the path on failure, also when a target is not a file it may replace (see
// the top of this file).
void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

// Writes `content` to `path` atomically. Throws std::runtime_error naming the
// path on failure; the previous file, if any, is then left as it was.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace idbench
