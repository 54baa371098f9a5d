// EnumNames: names round-trip through Parse and Name in the enum's order, and
// a bad name gets one message naming the field and listing the choices.
#include "idbench/engine/enum_names.h"

#include <gtest/gtest.h>

namespace idbench {
namespace {

enum class Fruit { kApple, kPear, kPlum };
constexpr EnumNames<Fruit, 3> kFruitNames{"fruit", {"apple", "pear", "plum"}};
enum class Side { kLeft, kRight };
constexpr EnumNames<Side, 2> kSideNames{"side", {"left", "right"}, true};

TEST(EnumNamesTest, NamesRoundTrip) {
  for (Fruit f : {Fruit::kApple, Fruit::kPear, Fruit::kPlum}) {
    Fruit parsed = Fruit::kApple;
    ASSERT_TRUE(kFruitNames.Parse(kFruitNames.Name(f), &parsed));
    EXPECT_EQ(parsed, f);
  }
  EXPECT_EQ(kFruitNames.Name(Fruit::kPlum), "plum");
  EXPECT_EQ(kFruitNames.Names(), (std::vector<std::string>{"apple", "pear", "plum"}));
}

TEST(EnumNamesTest, BadNameNamesFieldAndChoices) {
  Fruit f = Fruit::kPear;
  std::string why;
  EXPECT_FALSE(kFruitNames.Parse("Apple", &f, &why));
  EXPECT_EQ(f, Fruit::kPear);  // unchanged
  EXPECT_EQ(why, "fruit: expected apple, pear or plum, got 'Apple'");
  Side s = Side::kLeft;
  EXPECT_FALSE(kSideNames.Parse("", &s, &why));
  EXPECT_EQ(why, "side: expected 'left' or 'right', got ''");
  EXPECT_FALSE(kSideNames.Parse("left ", &s));  // no message asked for
}

}  // namespace
}  // namespace idbench
