// The CDR reader on hand-made buffers: alignment counted from after the
// 4-byte encapsulation header (a float64 after an odd-length string lands on a
// body offset that is 8-aligned but not file-aligned), both byte orders, and
// items that overrun the message.
#include "rosbag2/cdr_reader.h"

#include "logs/rosbag2/cdr_bytes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace idbench::internal {
namespace {

using testing::Put;
using testing::PutDouble;

// header | string "ab" (length 3 with NUL: body bytes 0..6) | pad to body 8 |
// uint32 count 2 (body 8..11) | pad to body 16 | 2 float64 (body 16..31) |
// int32 -7 (body 32..35) | string sequence {"", "xyz"}.
// Offsets written out by hand, independent of the reader's arithmetic.
std::vector<std::uint8_t> Message(bool big_endian) {
  std::vector<std::uint8_t> m = {0x00, static_cast<std::uint8_t>(big_endian ? 0x00 : 0x01), 0x00, 0x00};
  Put(m, 3, 4, big_endian);
  m.insert(m.end(), {'a', 'b', 0});
  m.push_back(0xEE);  // padding: body 7
  Put(m, 2, 4, big_endian);
  m.insert(m.end(), 4, 0xEE);  // padding: body 12..15
  PutDouble(m, 1.5, big_endian);
  PutDouble(m, -0.1, big_endian);
  Put(m, static_cast<std::uint32_t>(-7), 4, big_endian);
  Put(m, 2, 4, big_endian);
  Put(m, 1, 4, big_endian);
  m.push_back(0);  // "" with its NUL: body 44
  m.insert(m.end(), 3, 0xEE);  // padding: body 45..47
  Put(m, 4, 4, big_endian);
  m.insert(m.end(), {'x', 'y', 'z', 0});
  return m;
}

void ExpectReads(const std::vector<std::uint8_t>& m) {
  CdrReader cdr(m.data(), m.size());
  std::string s;
  cdr.ReadString("s", &s);
  EXPECT_EQ(s, "ab");
  std::vector<double> values;
  cdr.ReadFloat64Sequence("values", &values);
  EXPECT_EQ(values, (std::vector<double>{1.5, -0.1}));
  EXPECT_EQ(cdr.offset(), 4u + 32u);
  EXPECT_EQ(cdr.ReadInt32("i"), -7);
  std::vector<std::string> names;
  cdr.ReadStringSequence("names", &names);
  EXPECT_EQ(names, (std::vector<std::string>{"", "xyz"}));
  EXPECT_EQ(cdr.offset(), m.size());
}

TEST(CdrReaderTest, AlignsFromAfterTheHeaderLittleEndian) { ExpectReads(Message(false)); }

TEST(CdrReaderTest, ReadsBigEndianToo) {
  const std::vector<std::uint8_t> m = Message(true);
  EXPECT_TRUE(CdrReader(m.data(), m.size()).big_endian());
  ExpectReads(m);
}

TEST(CdrReaderTest, RefusesOverrunsAndOtherEncapsulations) {
  std::vector<std::uint8_t> m = Message(false);
  m.resize(30);  // cut inside the float64s
  CdrReader cdr(m.data(), m.size());
  std::string s;
  cdr.ReadString("s", &s);
  std::vector<double> values;
  try {
    cdr.ReadFloat64Sequence("position", &values);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field 'position'"), std::string::npos) << e.what();
  }
  // A count of 2^32 - 1 float64 is refused before anything is allocated.
  std::vector<std::uint8_t> huge = {0, 1, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF};
  CdrReader big(huge.data(), huge.size());
  EXPECT_THROW(big.ReadFloat64Sequence("effort", &values), std::invalid_argument);
  const std::vector<std::uint8_t> xcdr2 = {0x00, 0x07, 0, 0, 0, 0, 0, 0};  // D_CDR2_LE
  EXPECT_THROW(CdrReader(xcdr2.data(), xcdr2.size()), std::invalid_argument);
  EXPECT_THROW(CdrReader(xcdr2.data(), 3), std::invalid_argument);
}

}  // namespace
}  // namespace idbench::internal
