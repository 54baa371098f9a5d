#include "column_names.h"

#include <gtest/gtest.h>

#include "engine/test_util.h"

#include <string>

#include "idbench/engine/puma560.h"

namespace idbench::internal {
namespace {

using testing::ExpectInvalid;

// Each kind of column with its joint counted from 0, "_" skipped (kind -1),
// and anything else refused.
TEST(ColumnNamesTest, ParsesEveryKindOfColumn) {
  const struct {
    const char* name;
    int kind, joint;
  } cases[] = {{"t", 0, 0}, {"q1", 1, 0}, {"qd12", 2, 11}, {"qdd3", 3, 2}, {"tau6", 4, 5}, {"i2", 5, 1}, {"_", -1, 0}};
  for (const auto& c : cases) {
    ColumnTarget target{7, 7};
    ASSERT_TRUE(ParseColumnName(c.name, &target)) << c.name;
    EXPECT_EQ(target.kind, c.kind) << c.name;
    EXPECT_EQ(target.joint, c.joint) << c.name;
  }
  ColumnTarget target{};
  for (const char* bad : {"", "q", "q0", "1", "x1", "q1a", "q-1", "T"}) EXPECT_FALSE(ParseColumnName(bad, &target)) << bad;
  EXPECT_EQ(ColumnLabel(2, "tau1"), "column 3 ('tau1')");
}

// A header's q.<joint name> becomes the joint's number; idbench's own names
// stay; another vendor's name is ""; an unknown joint name is another
// robot's log.
TEST(ColumnNamesTest, HeaderNamesOfJointsBecomeNumbers) {
  const RobotModel puma = MakePuma560();
  const std::string joint3 = puma.link(2).joint_name;
  EXPECT_EQ(IdbenchColumnName("qd." + joint3, 0, puma, "f.csv:1: "), "qd3");
  EXPECT_EQ(IdbenchColumnName("tau4", 0, puma, "f.csv:1: "), "tau4");
  EXPECT_EQ(IdbenchColumnName("Joint_1", 0, puma, "f.csv:1: "), "");
  EXPECT_EQ(IdbenchColumnName("_", 0, puma, "f.csv:1: "), "");
  EXPECT_NE(ExpectInvalid([&] { IdbenchColumnName("q.elbow", 4, puma, "f.csv:1: "); })
                .find("f.csv:1: column 5 ('q.elbow'): no joint 'elbow' in"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench::internal
