#include "idbench/engine/printable_text.h"

#include <gtest/gtest.h>

#include <string>

namespace idbench {
namespace {

TEST(PrintableTextTest, KeepsPrintableAsciiAndUtf8) {
  EXPECT_EQ(PrintableText("joint_1 [rad]"), "joint_1 [rad]");
  EXPECT_EQ(PrintableText("Δq → τ"), "Δq → τ");
}

TEST(PrintableTextTest, EscapesControlBytesTheBomAndInvalidUtf8) {
  EXPECT_EQ(PrintableText(std::string("a\0b\x01\t\r\n", 7)), "a\\x00b\\x01\\t\\r\\n");
  EXPECT_EQ(PrintableText("\xef\xbb\xbft"), "\\xef\\xbb\\xbft");  // the UTF-8 byte order mark
  EXPECT_EQ(PrintableText("\xff\xc3"), "\\xff\\xc3");              // not UTF-8; a cut sequence
  EXPECT_EQ(PrintableText("\xc0\xaf"), "\\xc0\\xaf");              // overlong '/'
  EXPECT_EQ(PrintableText("\xc2\x85"), "\\xc2\\x85");              // C1 control NEL
}

TEST(PrintableTextTest, CutsLongTextGivingItsLength) {
  const std::string binary(100000, '\x07');
  const std::string shown = PrintableText(binary, 8);
  EXPECT_EQ(shown, "\\x07\\x07\\x07\\x07\\x07\\x07\\x07\\x07… (100000 bytes)");
  EXPECT_EQ(PrintableText(std::string(64, 'a')), std::string(64, 'a'));
  EXPECT_EQ(PrintableText(std::string(65, 'a')), std::string(64, 'a') + "… (65 bytes)");
}

TEST(PrintableTextTest, FindsTheFirstByteThatIsNotUtf8) {
  EXPECT_EQ(FindInvalidUtf8("plain Δq → τ \xef\xbb\xbf"), std::string_view::npos);
  EXPECT_EQ(FindInvalidUtf8(std::string("a\0b", 3)), std::string_view::npos);  // NUL is UTF-8
  EXPECT_EQ(FindInvalidUtf8("ab\xce"), 2u);          // a sequence cut by the end
  EXPECT_EQ(FindInvalidUtf8("ab\xce<"), 2u);         // ... or by an ASCII byte
  EXPECT_EQ(FindInvalidUtf8("a\x80"), 1u);           // a stray continuation byte
  EXPECT_EQ(FindInvalidUtf8("Δ\xed\xa0\x80"), 2u);  // a surrogate
  EXPECT_EQ(FindInvalidUtf8("\xf5\x80\x80\x80"), 0u);  // beyond U+10FFFF
}

}  // namespace
}  // namespace idbench
