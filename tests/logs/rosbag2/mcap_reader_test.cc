// The MCAP reader on files written by npm's @mcap/core (tests/data/bags):
// topics and types, messages of one topic in order, each chunk compression,
// and the damaged files (README there says where each is damaged).
#include "rosbag2/mcap_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "logs/rosbag2/bag_fixtures.h"

namespace idbench::internal {
namespace {

using testing::kBags;

// The /joint_states messages' count and their log times in ns (first, last).
struct Count {
  int n = 0;
  std::int64_t first = -1, last = -1;
  std::size_t size = 0;  // of the first message
};

Count CountMessages(McapReader& reader, const std::string& topic) {
  reader.Select(topic);
  Count count;
  BagMessage message;
  while (reader.Next(&message)) {
    if (count.n == 0) {
      count.first = message.log_time_ns;
      count.size = message.size;
    }
    count.last = message.log_time_ns;
    ++count.n;
  }
  return count;
}

TEST(McapReaderTest, ReadsEveryChunkCompression) {
  for (const char* file : {"joint_states_none.mcap", "joint_states_lz4.mcap", "joint_states_zstd.mcap"}) {
    McapReader reader((kBags / file).string());
    ASSERT_EQ(reader.topics().size(), 2u) << file;
    EXPECT_EQ(reader.topics()[0].name, "/other");
    EXPECT_EQ(reader.topics()[0].type, "std_msgs/msg/String");
    EXPECT_EQ(reader.topics()[1].name, "/joint_states");
    EXPECT_EQ(reader.topics()[1].type, "sensor_msgs/msg/JointState");
    EXPECT_EQ(reader.topics()[1].serialization, "cdr");
    const Count states = CountMessages(reader, "/joint_states");
    EXPECT_EQ(states.n, 200) << file;
    EXPECT_EQ(states.first, 1'000'000'000);
    EXPECT_EQ(states.last, 1'000'000'000 + 199 * 10'000'000LL);
    EXPECT_EQ(states.size, 316u);  // the README's message layout
    EXPECT_EQ(CountMessages(reader, "/other").n, 4) << file;
    EXPECT_EQ(CountMessages(reader, "/joint_states").n, 200) << file;  // Select starts over
  }
}

// The message reading every /joint_states message of `path` throws
// (std::invalid_argument), or "(no error)".
std::string ReadingError(const std::string& path) {
  try {
    McapReader reader(path);
    CountMessages(reader, "/joint_states");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

// The same for a fixture of tests/data/bags.
std::string Error(const std::string& file) { return ReadingError((kBags / file).string()); }

TEST(McapReaderTest, RefusesACrcMismatchAndATruncatedFile) {
  EXPECT_EQ(Error("bad_crc.mcap"),
            "Chunk record at offset 4508: CRC mismatch: the decompressed records have CRC-32 3126000633, "
            "the chunk records 716477711");
  EXPECT_EQ(Error("truncated.mcap"),
            "unexpected end of file in Chunk record at offset 4642 (a record of 2054 bytes, the file ends at 5669: truncated)");
  // Damage found only when reading reaches it: the topics before it are known.
  McapReader truncated((kBags / "truncated.mcap").string());
  EXPECT_EQ(truncated.topics().size(), 2u);
}

TEST(McapReaderTest, RefusesAFileWithoutTheMagic) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "idbench_mcap_reader_test.mcap";
  std::ofstream(path) << "t,q1\n0,0\n";
  EXPECT_THROW(McapReader(path.string()), std::invalid_argument);
  std::filesystem::remove(path);
}

// A fixture's bytes with `value` written little endian over `bytes` bytes at
// `offset`, saved as a scratch file; its path.
std::string Patched(const std::string& fixture, std::uint64_t offset, std::uint64_t value, int bytes,
                    const std::string& name) {
  std::ifstream in(kBags / fixture, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (int i = 0; i < bytes; ++i) data.at(offset + static_cast<std::uint64_t>(i)) = static_cast<char>(value >> (8 * i));
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary).write(data.data(), static_cast<std::streamsize>(data.size()));
  return path.string();
}

std::uint64_t LittleEndianAt(const std::string& fixture, std::uint64_t offset, int bytes) {
  std::ifstream in(kBags / fixture, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(offset));
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= static_cast<std::uint64_t>(static_cast<unsigned char>(in.get())) << (8 * i);
  return value;
}

// Issue 35 item 17: a chunk's uncompressed_size of 2^31 - 1 over 2 KB of
// Zstandard records (the zstd fixture's chunk #2 at offset 4642, README's
// layout) is refused before anything is allocated, naming the chunk and the
// field; the old reader allocated 2.1 GB for it.
TEST(McapReaderTest, RefusesAnUncompressedSizeItsRecordsCannotGive) {
  // Chunk record: opcode, length (8), message_start_time (8), message_end_time (8), uncompressed_size (8) at
  // byte 25, uncompressed_crc (4), compression (4 + 4 "zstd"), records length (8) at byte 45.
  constexpr std::uint64_t kChunk = 4642;
  ASSERT_EQ(LittleEndianAt("joint_states_zstd.mcap", kChunk, 1), 0x06u);
  const std::uint64_t records = LittleEndianAt("joint_states_zstd.mcap", kChunk + 45, 8);
  ASSERT_GT(records, 100u);
  ASSERT_LT(records * McapReader::kMaxZstdRatio, (std::uint64_t{1} << 31) - 1);
  const std::string path = Patched("joint_states_zstd.mcap", kChunk + 25, (std::uint64_t{1} << 31) - 1, 8,
                                   "idbench_mcap_huge_chunk.mcap");
  const std::string error = ReadingError(path);
  EXPECT_EQ(error, "Chunk record at offset 4642: uncompressed_size 2147483647 bytes, but " + std::to_string(records) +
                       " bytes of zstd records give at most " + std::to_string(records * 32768) +
                       " (the file is damaged)");
  std::filesystem::remove(path);
}

// The offset of a fixture's first Chunk record (records walked from the magic).
std::uint64_t FirstChunk(const std::string& fixture) {
  std::uint64_t offset = 8;
  while (LittleEndianAt(fixture, offset, 1) != 0x06) offset += 9 + LittleEndianAt(fixture, offset + 1, 8);
  return offset;
}

// The decompressed records grow as they arrive: an uncompressed_size within
// the bound but larger (or smaller) than what the records give is named, for
// either compression, and the chunk with its own size still reads.
TEST(McapReaderTest, NamesAnUncompressedSizeTheRecordsDoNotGive) {
  for (const std::string compression : {"lz4", "zstd"}) {
    const std::string fixture = "joint_states_" + compression + ".mcap";
    const std::uint64_t chunk = FirstChunk(fixture);
    const std::uint64_t size = LittleEndianAt(fixture, chunk + 25, 8);
    ASSERT_GT(size, 1000u) << fixture;
    const std::string where = "Chunk record at offset " + std::to_string(chunk) + ": ";
    const std::string gives = compression == "lz4" ? "LZ4 frame gives " : "Zstandard gives ";
    const std::string says = compression == "lz4" ? ", the chunk's uncompressed_size is " : ", uncompressed_size says ";
    const std::uint64_t records = LittleEndianAt(fixture, chunk + 41 + compression.size(), 8);
    const std::uint64_t ratio = compression == "lz4" ? McapReader::kMaxLz4Ratio : McapReader::kMaxZstdRatio;
    for (const std::uint64_t wrong : {size + 1, records * ratio, size - 1}) {
      const std::string path = Patched(fixture, chunk + 25, wrong, 8, "idbench_mcap_wrong_size.mcap");
      const std::string error = ReadingError(path);
      const std::string expected = where + gives + (wrong > size ? std::to_string(size) : std::to_string(wrong) +
                                                    " bytes and does not end") ;
      EXPECT_EQ(error.substr(0, expected.size()), expected) << error;
      EXPECT_NE(error.find(says + std::to_string(wrong)), std::string::npos) << error;
      std::filesystem::remove(path);
    }
  }
}

// Issue 35 item 21: a Footer whose summary_start does not lead to a summary
// (here one byte into the first chunk of the intact file) is not a truncated
// file: the data section is read, every message as in the original.
TEST(McapReaderTest, ReadsTheDataSectionWhenTheFooterPointsWrong) {
  const std::string fixture = "joint_states_none.mcap";
  const std::uint64_t size = std::filesystem::file_size(kBags / fixture);
  // The Footer: opcode and length (9 bytes), summary_start (8), summary_offset_start (8), summary_crc (4); magic (8).
  const std::uint64_t footer = size - 8 - 29;
  ASSERT_EQ(LittleEndianAt(fixture, footer, 1), 0x02u);
  const std::uint64_t summary_start = LittleEndianAt(fixture, footer + 9, 8);
  ASSERT_GT(summary_start, 4509u);
  for (const std::uint64_t wrong : {std::uint64_t{4509}, summary_start + 3, size - 40}) {
    const std::string path = Patched(fixture, footer + 9, wrong, 8, "idbench_mcap_bad_footer.mcap");
    McapReader reader(path);
    ASSERT_EQ(reader.topics().size(), 2u) << wrong;  // in the order the data section has them
    EXPECT_EQ(reader.topics()[0].name + " " + reader.topics()[1].name, "/joint_states /other");
    const Count states = CountMessages(reader, "/joint_states");
    EXPECT_EQ(states.n, 200) << wrong;
    EXPECT_EQ(states.last, 1'000'000'000 + 199 * 10'000'000LL);
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace idbench::internal
