// The SQLite3 storage reader on bags written by Python's sqlite3
// (tests/data/bags/make_db3.py): topics, one topic's rows in time order.
#include "rosbag2/db3_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include "logs/rosbag2/bag_fixtures.h"

namespace idbench::internal {
namespace {

using testing::kBags;

TEST(Db3ReaderTest, ReadsTopicsAndOneTopicsMessagesInTimeOrder) {
  Db3Reader reader((kBags / "bag_db3" / "bag_db3_0.db3").string());
  ASSERT_EQ(reader.topics().size(), 2u);
  EXPECT_EQ(reader.topics()[0].name, "/other");
  EXPECT_EQ(reader.topics()[1].name, "/joint_states");
  EXPECT_EQ(reader.topics()[1].type, "sensor_msgs/msg/JointState");
  for (int pass = 0; pass < 2; ++pass) {
    reader.Select("/joint_states");
    BagMessage message;
    int n = 0;
    while (reader.Next(&message)) {
      EXPECT_EQ(message.log_time_ns, 1'000'000'000 + n * 10'000'000LL);
      EXPECT_EQ(message.size, 316u);
      ++n;
    }
    EXPECT_EQ(n, 200);
  }
  reader.Select("/nowhere");
  BagMessage message;
  EXPECT_FALSE(reader.Next(&message));
}

TEST(Db3ReaderTest, RefusesWhatIsNotABag) {
  EXPECT_THROW(Db3Reader((kBags / "expected.csv").string()), std::invalid_argument);
  EXPECT_THROW(Db3Reader((kBags / "no_such.db3").string()), std::invalid_argument);
}

}  // namespace
}  // namespace idbench::internal
