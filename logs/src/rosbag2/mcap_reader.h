// An MCAP file (https://mcap.dev/spec, the default rosbag2 storage since ROS 2
// Iron) read as a stream of one topic's messages. Records are parsed by hand
// (no Debian package reads MCAP); chunks are decompressed one at a time with
// liblz4 (LZ4 frame format) or libzstd, and their CRC-32 (zlib) checked.
// Memory: one chunk (compressed and decompressed), whatever the file's length.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bag_message_reader.h"

namespace idbench::internal {

class McapReader final : public BagMessageReader {
 public:
  // Checks the magic and learns the topics: from the summary section when the
  // file ends with a Footer whose summary can be read, else by a pass over the
  // data section (which stops quietly at damage; Next reports it when reading
  // reaches it). Throws std::invalid_argument "path: what" for a path that is
  // not a regular file (a directory, a FIFO: OpenStreamedInputFile's words),
  // and "what" for a file that does not start with the MCAP magic.
  explicit McapReader(const std::string& path);
  ~McapReader() override;
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;

  const std::vector<BagTopic>& topics() const override { return topics_; }
  void Select(const std::string& topic) override;
  // Messages in file order. Throws std::invalid_argument naming the record
  // and its offset: "unexpected end of file in Chunk record at offset 4642
  // ...", a chunk's CRC mismatch, an unknown compression, a record that
  // overruns its chunk, a Message on a channel no Channel record defined.
  bool Next(BagMessage* message) override;
  std::string LastRecord() const override { return last_record_.Describe(); }

  // A chunk's uncompressed_size is checked before anything is allocated: at
  // most kMaxChunkBytes, and at most what its compressed records can give:
  // their size itself when stored, times kMaxLz4Ratio for an LZ4 frame (a
  // sequence's length bytes add at most 255 bytes each), times kMaxZstdRatio
  // for Zstandard (every block costs at least 4 bytes, a 3-byte header and one
  // byte, and gives at most 128 KiB).
  static constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 31;  // a chunk's decompressed size
  static constexpr std::uint64_t kMaxLz4Ratio = 255;
  static constexpr std::uint64_t kMaxZstdRatio = 128 * 1024 / 4;

 private:
  // Where a record is, described only for a message (not per record read).
  struct RecordPlace {
    std::uint8_t opcode = 0;
    std::uint64_t offset = 0;      // of the record in the file, or of its Chunk record
    std::int64_t chunk_byte = -1;  // of the record in its chunk's records; -1: a top-level record
    std::string Describe() const;  // "Message record at byte 3864 of the Chunk record at offset 17768"
  };
  struct Channel {
    std::string topic;
    std::uint16_t schema_id = 0;
    std::string message_encoding;
  };
  // Reads the records from `start` on without handing out messages, to learn
  // the schemas and channels.
  void Scan(std::uint64_t start);
  void ReadAt(std::uint64_t offset, std::size_t n, std::uint8_t* out);
  // Decompresses the Chunk record in record_ (at file offset `offset`) into
  // chunk_ and checks its CRC.
  void OpenChunk(std::uint64_t offset);
  // A Schema, Channel or Message record; true when it is a message to hand
  // out (then *message is filled).
  bool HandleRecord(const RecordPlace& place, const std::uint8_t* content, std::uint64_t length,
                    BagMessage* message);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t data_end_ = 0;  // where top-level records end: before the trailing magic, or the file's end
  std::uint64_t offset_ = 0;    // the next top-level record
  bool done_ = false;           // the Footer or DataEnd was reached
  std::vector<std::uint8_t> record_;  // the current top-level record's content
  std::vector<std::uint8_t> chunk_;   // the current chunk's records, decompressed
  std::size_t chunk_pos_ = 0;
  std::uint64_t chunk_offset_ = 0;
  bool in_chunk_ = false;
  bool selecting_ = false;  // hand out messages of selected_
  std::string selected_;
  std::map<std::uint16_t, std::string> schema_names_;
  std::map<std::uint16_t, Channel> channels_;
  std::vector<BagTopic> topics_;
  RecordPlace last_record_;
};

}  // namespace idbench::internal
