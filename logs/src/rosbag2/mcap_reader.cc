#include "mcap_reader.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "idbench/engine/input_file.h"

namespace idbench::internal {
namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint64_t kRecordHeaderBytes = 9;  // opcode (1) and content length (8)
constexpr std::uint64_t kFooterBytes = kRecordHeaderBytes + 20;

enum Opcode : std::uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kDataEnd = 0x0F,
};

std::string RecordName(std::uint8_t opcode) {
  static const char* const kNames[] = {"",           "Header",          "Footer",     "Schema",         "Channel",
                                       "Message",    "Chunk",           "MessageIndex", "ChunkIndex",   "Attachment",
                                       "AttachmentIndex", "Statistics", "Metadata",   "MetadataIndex", "SummaryOffset",
                                       "DataEnd"};
  if (opcode >= 1 && opcode <= 0x0F) return kNames[opcode];
  return "opcode " + std::to_string(opcode);
}

std::uint64_t Le(const std::uint8_t* p, int bytes) {
  std::uint64_t value = 0;
  for (int i = bytes - 1; i >= 0; --i) value = value << 8 | p[i];
  return value;
}

// The fields of one record, little endian, each checked against the record's
// length; `where` names the record in messages.
template <typename Where>
class Fields {
 public:
  Fields(const std::uint8_t* data, std::uint64_t size, const Where& where) : data_(data), size_(size), where_(where) {}
  std::uint64_t Uint(int bytes, const char* field) { return Le(Take(static_cast<std::uint64_t>(bytes), field), bytes); }
  std::string String(const char* field) {
    const std::uint64_t n = Uint(4, field);
    const std::uint8_t* p = Take(n, field);
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  // Bytes after a length prefix of `prefix_bytes` (4 or 8).
  const std::uint8_t* Bytes(int prefix_bytes, const char* field, std::uint64_t* n) {
    *n = Uint(prefix_bytes, field);
    return Take(*n, field);
  }
  const std::uint8_t* Rest(std::uint64_t* n) {
    *n = size_ - pos_;
    return data_ + pos_;
  }

 private:
  const std::uint8_t* Take(std::uint64_t n, const char* field) {
    if (n > size_ - pos_) {
      throw std::invalid_argument(Text(where_) + ": field " + field + " (" + std::to_string(n) + " bytes at byte " +
                                  std::to_string(pos_) + ") overruns the record of " + std::to_string(size_) +
                                  " bytes");
    }
    pos_ += n;
    return data_ + pos_ - n;
  }
  const std::uint8_t* data_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
  static std::string Text(const std::string& where) { return where; }
  template <typename Place>
  static std::string Text(const Place& place) { return place.Describe(); }
  const Where& where_;
};

// The output of a decompression grows as it arrives (doubling from a few
// times the compressed size, up to the chunk's uncompressed_size), so a
// forged uncompressed_size or frame header never allocates much more than
// the records really give.
std::size_t FirstOutputBytes(std::size_t in_size, std::size_t expected) {
  return std::min(expected, std::max<std::size_t>(4 * in_size, 64 * 1024));
}

// Doubles `out` up to `expected` bytes; false when it is that large already.
bool GrowOutput(std::vector<std::uint8_t>& out, std::size_t expected) {
  if (out.size() >= expected) return false;
  out.resize(std::min(expected, 2 * out.size()));
  return true;
}

// Decompresses an LZ4 frame (not a raw block) into `out`, which must come to
// exactly `expected` bytes.
void DecompressLz4Frame(const std::uint8_t* in, std::size_t in_size, std::size_t expected,
                        std::vector<std::uint8_t>& out, const std::string& where) {
  LZ4F_dctx* context = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
    throw std::invalid_argument(where + ": LZ4 context not created");
  }
  out.resize(FirstOutputBytes(in_size, expected));
  std::size_t read = 0, written = 0;
  std::size_t hint = 1;
  while (hint != 0 && read < in_size) {
    std::size_t in_step = in_size - read, out_step = out.size() - written;
    hint = LZ4F_decompress(context, out.data() + written, &out_step, in + read, &in_step, nullptr);
    if (LZ4F_isError(hint)) {
      const std::string why = LZ4F_getErrorName(hint);
      LZ4F_freeDecompressionContext(context);
      throw std::invalid_argument(where + ": LZ4 frame: " + why);
    }
    read += in_step;
    written += out_step;
    const bool grew = written == out.size() && GrowOutput(out, expected);
    if (in_step == 0 && out_step == 0 && !grew) break;  // output full at uncompressed_size, frame not done
  }
  LZ4F_freeDecompressionContext(context);
  if (hint != 0 || written != expected) {
    throw std::invalid_argument(where + ": LZ4 frame gives " + std::to_string(written) + " bytes" +
                                (hint != 0 ? " and does not end" : "") + ", the chunk's uncompressed_size is " +
                                std::to_string(expected));
  }
}

// Decompresses Zstandard frames into `out`, which must come to exactly
// `expected` bytes (ZSTD_decompress's result, streamed so that `out` grows).
void DecompressZstd(const std::uint8_t* in, std::size_t in_size, std::size_t expected, std::vector<std::uint8_t>& out,
                    const std::string& where) {
  ZSTD_DCtx* context = ZSTD_createDCtx();
  if (context == nullptr) throw std::invalid_argument(where + ": Zstandard context not created");
  out.resize(FirstOutputBytes(in_size, expected));
  ZSTD_inBuffer input{in, in_size, 0};
  std::size_t written = 0, hint = 1;
  for (;;) {
    ZSTD_outBuffer output{out.data() + written, out.size() - written, 0};
    hint = ZSTD_decompressStream(context, &output, &input);
    if (ZSTD_isError(hint)) {
      const std::string why = ZSTD_getErrorName(hint);
      ZSTD_freeDCtx(context);
      throw std::invalid_argument(where + ": Zstandard: " + why);
    }
    written += output.pos;
    if (input.pos == input.size && output.pos < output.size) break;  // all read, all flushed
    if (written == out.size() && !GrowOutput(out, expected)) break;  // output full at uncompressed_size
  }
  ZSTD_freeDCtx(context);
  if (hint != 0 || input.pos != input.size || written != expected) {
    throw std::invalid_argument(where + ": Zstandard gives " + std::to_string(written) + " bytes" +
                                (hint != 0 || input.pos != input.size ? " and does not end" : "") +
                                ", uncompressed_size says " + std::to_string(expected));
  }
}

}  // namespace

McapReader::McapReader(const std::string& path) : path_(path) {
  // Only a regular file: a FIFO would block the open, a directory named
  // bag_0.mcap is named as one.
  const int fd = OpenStreamedInputFile(path);
  file_ = ::fdopen(fd, "rb");
  if (file_ == nullptr) {
    ::close(fd);
    throw std::invalid_argument("cannot open the file: " + std::string(std::strerror(errno)));
  }
  std::fseek(file_, 0, SEEK_END);
  const std::uint64_t file_size = static_cast<std::uint64_t>(ftello(file_));
  data_end_ = file_size;
  std::uint8_t magic[8] = {};
  if (file_size < 8 || (ReadAt(0, 8, magic), std::memcmp(magic, kMagic, 8) != 0)) {
    std::fclose(file_);
    file_ = nullptr;
    throw std::invalid_argument("not an MCAP file (it does not start with the MCAP magic)");
  }
  // A complete file ends with Footer and magic; the Footer points to the
  // summary, which repeats every Schema and Channel.
  std::uint64_t summary_start = 0;
  if (file_size >= 8 + kFooterBytes + 8) {
    std::uint8_t tail[kFooterBytes + 8];
    ReadAt(file_size - sizeof tail, sizeof tail, tail);
    if (std::memcmp(tail + kFooterBytes, kMagic, 8) == 0 && tail[0] == kFooter && Le(tail + 1, 8) == 20) {
      data_end_ = file_size - 8;
      summary_start = Le(tail + kRecordHeaderBytes, 8);
      if (summary_start >= data_end_) summary_start = 0;
    }
  }
  bool summary_read = false;
  if (summary_start != 0) {
    // A Footer's summary_start that does not lead to records ending at the
    // Footer (damaged, or pointing into the data section's middle) is not
    // the file's end being cut: the data section is read instead.
    try {
      Scan(summary_start);
      summary_read = true;
    } catch (const std::invalid_argument&) {
      schema_names_.clear();
      channels_.clear();
      topics_.clear();
    }
  }
  if (!summary_read) {
    // No summary (or no Footer: a truncated file): the data section's own
    // Schema and Channel records, up to the first damage, which Next reports.
    try {
      Scan(8);
    } catch (const std::invalid_argument&) {
    }
  }
  Select("");
  selecting_ = false;
}

McapReader::~McapReader() {
  if (file_ != nullptr) std::fclose(file_);
}

void McapReader::ReadAt(std::uint64_t offset, std::size_t n, std::uint8_t* out) {
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0 || std::fread(out, 1, n, file_) != n) {
    throw std::invalid_argument("read error at offset " + std::to_string(offset));
  }
}

void McapReader::Scan(std::uint64_t start) {
  selecting_ = false;
  offset_ = start;
  in_chunk_ = false;
  done_ = false;
  BagMessage ignored;
  while (Next(&ignored)) {
  }
}

void McapReader::Select(const std::string& topic) {
  selected_ = topic;
  selecting_ = true;
  offset_ = 8;
  in_chunk_ = false;
  done_ = false;
  last_record_ = RecordPlace();
}

bool McapReader::Next(BagMessage* message) {
  while (true) {
    // The records of the chunk being read.
    if (in_chunk_) {
      if (chunk_pos_ < chunk_.size()) {
        const RecordPlace place{chunk_.size() - chunk_pos_ >= 1 ? chunk_[chunk_pos_] : std::uint8_t{0}, chunk_offset_,
                                static_cast<std::int64_t>(chunk_pos_)};
        if (chunk_.size() - chunk_pos_ < kRecordHeaderBytes) {
          throw std::invalid_argument(place.Describe() + ": cut short");
        }
        const std::uint64_t length = Le(&chunk_[chunk_pos_ + 1], 8);
        if (length > chunk_.size() - chunk_pos_ - kRecordHeaderBytes) {
          throw std::invalid_argument(place.Describe() + ": " + std::to_string(length) + " bytes overrun the chunk");
        }
        const std::uint8_t* content = &chunk_[chunk_pos_ + kRecordHeaderBytes];
        chunk_pos_ += kRecordHeaderBytes + length;
        if (HandleRecord(place, content, length, message)) return true;
        continue;
      }
      in_chunk_ = false;
    }
    if (done_) return false;

    // The next top-level record.
    if (data_end_ - offset_ < kRecordHeaderBytes) {
      throw std::invalid_argument("unexpected end of file at offset " + std::to_string(offset_) +
                                  " (no Footer record: the file is truncated)");
    }
    std::uint8_t header[kRecordHeaderBytes];
    ReadAt(offset_, kRecordHeaderBytes, header);
    const std::uint8_t opcode = header[0];
    const std::uint64_t length = Le(header + 1, 8);
    const std::uint64_t offset = offset_;
    const RecordPlace place{opcode, offset};
    if (length > data_end_ - offset - kRecordHeaderBytes) {
      throw std::invalid_argument("unexpected end of file in " + place.Describe() + " (a record of " +
                                  std::to_string(kRecordHeaderBytes + length) + " bytes, the file ends at " + std::to_string(data_end_) + ": truncated)");
    }
    offset_ = offset + kRecordHeaderBytes + length;
    switch (opcode) {
      case kFooter:
      case kDataEnd:
        done_ = true;
        return false;
      case kChunk:
        record_.resize(length);
        ReadAt(offset + kRecordHeaderBytes, length, record_.data());
        OpenChunk(offset);
        break;
      case kSchema:
      case kChannel:
      case kMessage:
        record_.resize(length);
        ReadAt(offset + kRecordHeaderBytes, length, record_.data());
        if (HandleRecord(place, record_.data(), length, message)) return true;
        break;
      default:  // indexes, attachments, metadata, statistics: not needed
        break;
    }
  }
}

void McapReader::OpenChunk(std::uint64_t offset) {
  const std::string where = "Chunk record at offset " + std::to_string(offset);
  Fields fields(record_.data(), record_.size(), where);
  fields.Uint(8, "message_start_time");
  fields.Uint(8, "message_end_time");
  const std::uint64_t uncompressed_size = fields.Uint(8, "uncompressed_size");
  const std::uint32_t crc = static_cast<std::uint32_t>(fields.Uint(4, "uncompressed_crc"));
  const std::string compression = fields.String("compression");
  std::uint64_t compressed_size = 0;
  const std::uint8_t* records = fields.Bytes(8, "records", &compressed_size);
  if (!compression.empty() && compression != "lz4" && compression != "zstd") {
    throw std::invalid_argument(where + ": compression '" + compression + "' is not read (\"\", lz4 or zstd)");
  }

  // uncompressed_size within the stated bounds before it is allocated: what
  // the compressed records can give at most, and kMaxChunkBytes.
  if (compression.empty() && compressed_size != uncompressed_size) {
    throw std::invalid_argument(where + ": uncompressed chunk of " + std::to_string(compressed_size) +
                                " bytes, uncompressed_size says " + std::to_string(uncompressed_size));
  }
  const std::uint64_t ratio = compression == "lz4" ? kMaxLz4Ratio : compression == "zstd" ? kMaxZstdRatio : 1;
  if (uncompressed_size > compressed_size * ratio) {  // compressed_size is within the file: no overflow
    throw std::invalid_argument(where + ": uncompressed_size " + std::to_string(uncompressed_size) + " bytes, but " +
                                std::to_string(compressed_size) + " bytes of " + compression +
                                " records give at most " + std::to_string(compressed_size * ratio) +
                                " (the file is damaged)");
  }
  if (uncompressed_size > kMaxChunkBytes) {
    throw std::invalid_argument(where + ": uncompressed_size " + std::to_string(uncompressed_size) +
                                " bytes is beyond the " + std::to_string(kMaxChunkBytes) + " bytes of a chunk read");
  }
  if (compression.empty()) {
    chunk_.assign(records, records + compressed_size);
  } else if (compression == "lz4") {
    DecompressLz4Frame(records, compressed_size, uncompressed_size, chunk_, where);
  } else {  // zstd
    DecompressZstd(records, compressed_size, uncompressed_size, chunk_, where);
  }

  // CRC-32 of the decompressed records; 0 means not given.
  if (crc != 0) {
    const std::uint32_t actual = static_cast<std::uint32_t>(
        crc32_z(crc32_z(0L, Z_NULL, 0), chunk_.data(), static_cast<z_size_t>(chunk_.size())));
    if (actual != crc) {
      throw std::invalid_argument(where + ": CRC mismatch: the decompressed records have CRC-32 " +
                                  std::to_string(actual) + ", the chunk records " + std::to_string(crc));
    }
  }
  chunk_pos_ = 0;
  chunk_offset_ = offset;
  in_chunk_ = true;
}

std::string McapReader::RecordPlace::Describe() const {
  return chunk_byte < 0 ? RecordName(opcode) + " record at offset " + std::to_string(offset)
                        : RecordName(opcode) + " record at byte " + std::to_string(chunk_byte) +
                              " of the Chunk record at offset " + std::to_string(offset);
}

bool McapReader::HandleRecord(const RecordPlace& place, const std::uint8_t* content, std::uint64_t length,
                              BagMessage* message) {
  const std::uint8_t opcode = place.opcode;
  Fields fields(content, length, place);
  if (opcode == kSchema) {
    const auto id = static_cast<std::uint16_t>(fields.Uint(2, "id"));
    schema_names_[id] = fields.String("name");
    return false;
  }
  if (opcode == kChannel) {
    const auto id = static_cast<std::uint16_t>(fields.Uint(2, "id"));
    Channel channel;
    channel.schema_id = static_cast<std::uint16_t>(fields.Uint(2, "schema_id"));
    channel.topic = fields.String("topic");
    channel.message_encoding = fields.String("message_encoding");
    const auto found = std::find_if(topics_.begin(), topics_.end(),
                                    [&](const BagTopic& topic) { return topic.name == channel.topic; });
    if (found == topics_.end()) {
      const auto schema = schema_names_.find(channel.schema_id);
      topics_.push_back({channel.topic, schema == schema_names_.end() ? "" : schema->second,
                         channel.message_encoding});
    }
    channels_[id] = std::move(channel);
    return false;
  }
  if (opcode != kMessage || !selecting_) return false;
  const auto channel_id = static_cast<std::uint16_t>(fields.Uint(2, "channel_id"));
  fields.Uint(4, "sequence");
  const std::uint64_t log_time = fields.Uint(8, "log_time");
  fields.Uint(8, "publish_time");
  const auto channel = channels_.find(channel_id);
  if (channel == channels_.end()) {
    throw std::invalid_argument(place.Describe() + ": channel " + std::to_string(channel_id) +
                                ", which no Channel record before it defines");
  }
  if (channel->second.topic != selected_) return false;
  std::uint64_t size = 0;
  message->data = fields.Rest(&size);
  message->size = size;
  message->log_time_ns = static_cast<std::int64_t>(log_time);
  last_record_ = place;
  return true;
}

}  // namespace idbench::internal
