// A text file handed out line by line in bounded blocks (never the whole
// text), or a text already in memory handed out the same way: what every
// log reader reads lines through.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace idbench::internal {

class LineReader {
 public:
  // Reads `path` in blocks of kBlockBytes. Throws std::invalid_argument
  // "path: ..." when it cannot be opened or is not a regular file (a FIFO,
  // a device or a directory would block or mislead).
  static LineReader FromFile(const std::string& path);
  // Hands out the lines of `text`, which must outlive the reader; `source`
  // names it in messages.
  static LineReader FromText(std::string_view text, std::string source);

  LineReader(LineReader&& other) noexcept;
  LineReader& operator=(LineReader&& other) noexcept;
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;
  ~LineReader();

  // The next line into *line (without '\n'; valid until the next call), a
  // UTF-8 byte order mark dropped from the first. Returns false at the end.
  // A line longer than MaxLineBytes() throws "source:line: the line is N
  // bytes, longer than the limit ..." (input_file.h).
  bool Next(std::string_view* line);
  // The number of the line Next last gave (from 1); 0 before the first.
  std::int64_t line_number() const { return line_number_; }
  // Back to the first line.
  void Rewind();
  const std::string& source() const { return source_; }

  static constexpr std::size_t kBlockBytes = 1 << 20;

 private:
  LineReader() = default;
  // Reads more of the file after the unread part; false at its end.
  bool Fill();
  [[noreturn]] void FailLongLine(std::size_t bytes_so_far);

  std::string source_;
  int fd_ = -1;              // the file, or -1 for a text in memory
  std::string buffer_;       // the block being read (a file)
  std::string_view data_;    // what is held: the text, or buffer_'s filled part
  std::size_t next_ = 0;     // start of the unread part of data_
  bool at_end_ = false;      // no more to read into the buffer
  std::int64_t line_number_ = 0;
};

}  // namespace idbench::internal
