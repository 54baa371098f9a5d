#include "idbench/logs/joint_log_format.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace idbench {
namespace {

// Options: an empty column name is named with its position; drive gains of
// absurd magnitude or all negative are refused, one negative is allowed.
TEST(JointLogCsvTest, EmptyColumnNamesAndDriveGainBounds) {
  std::string why;
  JointLogFormat empty;
  empty.columns = {"t", "q1", "", "q3"};
  EXPECT_FALSE(empty.IsValid(&why));
  EXPECT_NE(why.find("column 3 is empty"), std::string::npos) << why;
  JointLogFormat gains;
  for (const std::vector<double>& bad : {std::vector<double>{1e-300, 1}, {1, 1e300}, {1, -1e-7}, {-10, -10}}) {
    gains.drive_gains = bad;
    EXPECT_FALSE(gains.IsValid(&why)) << bad[0] << "," << bad[1];
  }
  gains.drive_gains = {-10, -10};
  gains.IsValid(&why);
  EXPECT_NE(why.find("drive_gains: every gain is negative"), std::string::npos) << why;
  gains.drive_gains = {1e-6, -1e6};
  EXPECT_TRUE(gains.IsValid(&why)) << why;
}

}  // namespace
}  // namespace idbench
