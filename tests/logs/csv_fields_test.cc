#include "csv_fields.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace idbench::internal {
namespace {

// Fields are split on every comma (no quoting) and trimmed of spaces, tabs
// and a trailing '\r'; empty fields stay, as the column checks name them.
TEST(CsvFieldsTest, SplitsOnCommasAndTrims) {
  EXPECT_EQ(SplitFields("t, q1 ,\tq2\r"), (std::vector<std::string>{"t", "q1", "q2"}));
  EXPECT_EQ(SplitFields("1,,2,"), (std::vector<std::string>{"1", "", "2", ""}));
  EXPECT_EQ(SplitFields(""), (std::vector<std::string>{""}));
  EXPECT_EQ(SplitFields("  "), (std::vector<std::string>{""}));
}

// A data line has numbers only; one name, one empty or one partly numeric
// field makes it a header.
TEST(CsvFieldsTest, AllNumbersTellsDataFromAHeader) {
  EXPECT_TRUE(AllNumbers({"0", "-1.5e-3", "2"}));
  EXPECT_FALSE(AllNumbers({"0", "q1"}));
  EXPECT_FALSE(AllNumbers({"0", ""}));
  EXPECT_FALSE(AllNumbers({"1.5x"}));
}

}  // namespace
}  // namespace idbench::internal
