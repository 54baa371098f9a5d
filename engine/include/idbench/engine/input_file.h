// Reading a user's input file within bounds. Only a regular file is read: a
// FIFO, a device or a directory would block, never end, or mislead. A file
// larger than MaxInputFileBytes() is refused before anything is read.
#pragma once

#include <cstdint>
#include <cstddef>
#include <string>
#include <string_view>

namespace idbench {

// The largest input file idbench reads [bytes]: 1/16 of the machine's
// physical memory (a parser holds the text and a few times its size in
// parsed form), or IDBENCH_MAX_INPUT_MB megabytes when that environment
// variable is set (a positive integer).
std::uint64_t MaxInputFileBytes();

// The limit as a message shows it: "1536 MB (1/16 of this machine's memory;
// IDBENCH_MAX_INPUT_MB=N raises it)".
std::string InputLimitDescription();

// Throws std::invalid_argument starting with `path` when it does not exist, is
// not a regular file (saying what it is: a directory, FIFO, device, socket),
// or is larger than MaxInputFileBytes() (naming both sizes and how to raise
// the limit).
void CheckInputFile(const std::string& path);

// Whether paths a and b name the same file: the same string, or the same
// device and inode however spelled (./x.json and x.json, a hard or symbolic
// link). False when either cannot be stat()ed (its reader says why).
bool IsSameFile(const std::string& a, const std::string& b);

// The whole file after CheckInputFile. Opened without blocking, and checked
// again once open, so a FIFO swapped in after the check does not hang it.
// Throws std::invalid_argument as CheckInputFile, and when reading fails.
std::string ReadInputFile(const std::string& path);

// Opens `path` to be read in pieces (a streamed log, a bag's storage file):
// without blocking and without a size limit, as the file is never held whole.
// Throws std::invalid_argument as CheckInputFile when it is not a regular file
// (a directory, FIFO, device, socket), checked before and after opening, so a
// FIFO swapped in between does not hang it. Returns the open file descriptor
// (O_RDONLY | O_NONBLOCK, which a regular file ignores); the caller closes it.
int OpenStreamedInputFile(const std::string& path);

// The longest line idbench reads [bytes]: 64 KiB, room for the 1024 columns
// a joint log may have at 64 characters each (a double needs at most 24), or
// IDBENCH_MAX_LINE_KB kibibytes when that is set.
std::size_t MaxLineBytes();

// Throws std::invalid_argument "SOURCE:LINE: the line is N bytes, longer than
// the limit ..." for the first line of `text` longer than MaxLineBytes()
// (naming how to raise it), before a parser copies or splits it.
void CheckLineLengths(std::string_view text, const std::string& source);

}  // namespace idbench
