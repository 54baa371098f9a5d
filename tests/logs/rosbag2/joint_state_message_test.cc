// JointState decoding on a message laid out by hand (the layout of the
// fixtures' README: header at 4, names padded to 4, float64 aligned to 8
// counted from byte 4), and the refusal of arrays of different lengths.
#include "rosbag2/joint_state_message.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "logs/rosbag2/cdr_bytes.h"

namespace idbench::internal {
namespace {

using testing::Put;
using testing::PutDouble;

// stamp (7, 250000000), frame_id "w", names {"j2", "j1"}, position {0.5,
// -0.25} (or 1 entry when ragged), velocity {}, effort {3, 4}.
std::vector<std::uint8_t> JointStateBytes(bool ragged) {
  std::vector<std::uint8_t> m = {0x00, 0x01, 0x00, 0x00};
  Put(m, 7, 4);
  Put(m, 250000000, 4);
  Put(m, 2, 4);
  m.insert(m.end(), {'w', 0, 0xEE, 0xEE});  // frame_id: body 12..13, padding 14..15
  Put(m, 2, 4);                             // name count: body 16
  for (const char* name : {"j2", "j1"}) {   // body 20..26, pad 27; 28..34, pad 35
    Put(m, 3, 4);
    m.insert(m.end(), {static_cast<std::uint8_t>(name[0]), static_cast<std::uint8_t>(name[1]), 0, 0xEE});
  }
  Put(m, ragged ? 1 : 2, 4);  // position count: body 36..39, then float64 at 40
  PutDouble(m, 0.5);
  if (!ragged) PutDouble(m, -0.25);
  Put(m, 0, 4);  // velocity: empty (body 56, or 48 when ragged)
  Put(m, 2, 4);  // effort count at body 60 (or 52): its float64 at 64 (or 56) need no padding
  PutDouble(m, 3.0);
  PutDouble(m, 4.0);
  return m;
}

TEST(JointStateMessageTest, DecodesEveryField) {
  const std::vector<std::uint8_t> bytes = JointStateBytes(false);
  JointStateMessage message;
  DecodeJointState(bytes.data(), bytes.size(), &message);
  EXPECT_EQ(message.stamp_sec, 7);
  EXPECT_EQ(message.stamp_nanosec, 250000000u);
  EXPECT_EQ(message.frame_id, "w");
  EXPECT_EQ(message.name, (std::vector<std::string>{"j2", "j1"}));
  EXPECT_EQ(message.position, (std::vector<double>{0.5, -0.25}));
  EXPECT_TRUE(message.velocity.empty());
  EXPECT_EQ(message.effort, (std::vector<double>{3.0, 4.0}));
}

TEST(JointStateMessageTest, RefusesArraysOfAnotherLengthThanTheNames) {
  const std::vector<std::uint8_t> bytes = JointStateBytes(true);
  JointStateMessage message;
  try {
    DecodeJointState(bytes.data(), bytes.size(), &message);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "position has 1 entries, name has 2");
  }
}

}  // namespace
}  // namespace idbench::internal
