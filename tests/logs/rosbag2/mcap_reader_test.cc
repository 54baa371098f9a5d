// The MCAP reader on files written by npm's @mcap/core (tests/data/bags):
// topics and types, messages of one topic in order, each chunk compression,
// and the damaged files (README there says where each is damaged).
#include "rosbag2/mcap_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
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

std::string Error(const std::string& file) {
  try {
    McapReader reader((kBags / file).string());
    CountMessages(reader, "/joint_states");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

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

}  // namespace
}  // namespace idbench::internal
