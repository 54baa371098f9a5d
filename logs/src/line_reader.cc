#include "line_reader.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "idbench/engine/input_file.h"

namespace idbench::internal {
namespace {

constexpr std::string_view kBom = "\xef\xbb\xbf";

[[noreturn]] void FailErrno(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

LineReader LineReader::FromFile(const std::string& path) {
  LineReader reader;
  reader.source_ = path;
  reader.fd_ = OpenStreamedInputFile(path);  // a FIFO or a device is refused, not waited on
  reader.buffer_.resize(kBlockBytes);
  return reader;
}

LineReader LineReader::FromText(std::string_view text, std::string source) {
  LineReader reader;
  reader.source_ = std::move(source);
  reader.data_ = text;
  reader.at_end_ = true;
  return reader;
}

LineReader::LineReader(LineReader&& other) noexcept { *this = std::move(other); }

LineReader& LineReader::operator=(LineReader&& other) noexcept {
  if (this == &other) return *this;
  if (fd_ >= 0) ::close(fd_);
  const bool own = other.fd_ >= 0;
  source_ = std::move(other.source_);
  fd_ = std::exchange(other.fd_, -1);
  const std::size_t filled = own ? other.data_.size() : 0;
  buffer_ = std::move(other.buffer_);
  data_ = own ? std::string_view(buffer_.data(), filled) : other.data_;
  next_ = other.next_;
  at_end_ = other.at_end_;
  line_number_ = other.line_number_;
  return *this;
}

LineReader::~LineReader() {
  if (fd_ >= 0) ::close(fd_);
}

bool LineReader::Fill() {
  if (at_end_) return false;
  // The unread part moves to the front; the block grows only to hold one
  // line longer than a block (up to the line limit).
  const std::size_t kept = data_.size() - next_;
  std::memmove(buffer_.data(), buffer_.data() + next_, kept);
  if (kept == buffer_.size()) buffer_.resize(2 * buffer_.size());
  std::size_t filled = kept;
  while (filled < buffer_.size()) {
    const ssize_t n = ::read(fd_, buffer_.data() + filled, buffer_.size() - filled);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) FailErrno(source_, "error while reading the file");
    if (n == 0) {
      at_end_ = true;
      break;
    }
    filled += static_cast<std::size_t>(n);
  }
  data_ = std::string_view(buffer_.data(), filled);
  next_ = 0;
  return filled > kept;
}

void LineReader::FailLongLine(std::size_t bytes_so_far) {
  // Counts the rest of the line without holding it, to say how long it is.
  std::size_t length = bytes_so_far;
  if (data_.find('\n', next_) == std::string_view::npos) {
    length = data_.size() - next_;
    next_ = data_.size();
    while (Fill()) {
      const std::size_t newline = data_.find('\n');
      if (newline != std::string_view::npos) {
        length += newline;
        break;
      }
      length += data_.size();
      next_ = data_.size();
    }
  }
  // The message CheckLineLengths gives (how to raise the limit), at this line.
  try {
    CheckLineLengths(std::string(length, 'x'), "");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();  // ":1: the line is ..."
    throw std::invalid_argument(source_ + ":" + std::to_string(line_number_ + 1) + what.substr(what.find(": ")));
  }
  throw std::logic_error("LineReader: a line over the limit passed CheckLineLengths");
}

bool LineReader::Next(std::string_view* line) {
  const std::size_t limit = MaxLineBytes();
  for (;;) {
    const std::size_t newline = data_.find('\n', next_);
    if (newline != std::string_view::npos || (at_end_ && next_ < data_.size())) {
      const std::size_t end = newline == std::string_view::npos ? data_.size() : newline;
      if (end - next_ > limit) FailLongLine(end - next_);
      *line = data_.substr(next_, end - next_);
      next_ = end + (newline == std::string_view::npos ? 0 : 1);
      if (++line_number_ == 1 && line->starts_with(kBom)) line->remove_prefix(kBom.size());
      return true;
    }
    if (data_.size() - next_ > limit) FailLongLine(data_.size() - next_);
    if (!Fill()) {
      if (next_ < data_.size()) continue;  // a last line without '\n'
      return false;
    }
  }
}

void LineReader::Rewind() {
  line_number_ = 0;
  next_ = 0;
  if (fd_ < 0) return;
  if (::lseek(fd_, 0, SEEK_SET) < 0) FailErrno(source_, "cannot read the file again");
  data_ = {};
  at_end_ = false;
}

}  // namespace idbench::internal
