#include "idbench/logs/recorded_joint_log.h"

#include <gtest/gtest.h>

#include "engine/test_util.h"

#include <map>
#include <numbers>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/logs/joint_log_csv_reader.h"

namespace idbench {
namespace {

using testing::ExpectInvalid;

// Arrays (Python's dict logs) are read as a file is: the same text through
// the CSV reader gives the same log, with degrees converted and τ = K·i;
// errors name the array at fault.
TEST(JointLogCsvTest, ArraysAreReadAsAFileIs) {
  const RobotModel puma = MakePuma560();
  JointLogFormat format;
  format.angle_unit = "deg";
  format.drive_gains = {10, 20, 30, 40, -50, 60};
  std::map<std::string, Eigen::MatrixXd> arrays;
  arrays["t"] = Eigen::Vector3d(0.0, 0.01, 0.02);
  arrays["q"] = Eigen::MatrixXd(3, 6);
  arrays["qd"] = Eigen::MatrixXd(3, 6);
  arrays["i"] = Eigen::MatrixXd(3, 6);
  std::string text = "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,i1,i2,i3,i4,i5,i6\n";
  for (int s = 0; s < 3; ++s) {
    text += std::to_string(0.01 * s);
    for (const char* key : {"q", "qd", "i"}) {
      for (int j = 0; j < 6; ++j) {
        const double v = std::string(key) == "i" ? 0.5 * j - s : 10.0 * j + s;
        arrays[key](s, j) = v;
        text += "," + std::to_string(v);
      }
    }
    text += "\n";
  }
  const RecordedJointLog from_arrays = RecordedJointLogFromArrays(arrays, puma, "<arrays>", format, TorqueColumns::kRequired);
  const RecordedJointLog from_file = ParseRecordedJointLog(text, puma, "f.csv", format, TorqueColumns::kRequired);
  EXPECT_TRUE(from_arrays.torque_from_currents);
  EXPECT_EQ(from_arrays.log.t, from_file.log.t);
  EXPECT_EQ(from_arrays.log.q, from_file.log.q);
  EXPECT_EQ(from_arrays.log.qd, from_file.log.qd);
  EXPECT_EQ(from_arrays.log.tau, from_file.log.tau);
  EXPECT_DOUBLE_EQ(from_arrays.log.q(2, 3), 32.0 * std::numbers::pi / 180.0);
  EXPECT_DOUBLE_EQ(from_arrays.log.tau(1, 4), -50.0 * (0.5 * 4 - 1));
  EXPECT_DOUBLE_EQ(from_arrays.log.tau(0, 5), 60.0 * 2.5);
  // A short t is blamed on t, not on q; a missing i with gains names both.
  std::map<std::string, Eigen::MatrixXd> short_t = arrays;
  short_t["t"] = Eigen::Vector2d(0.0, 0.01);
  EXPECT_NE(ExpectInvalid([&] { RecordedJointLogFromArrays(short_t, puma, "<arrays>", format, TorqueColumns::kRequired); })
                .find("<arrays>: q: 3 rows but t has 2 samples: every array needs one row per sample of t"),
            std::string::npos);
  std::map<std::string, Eigen::MatrixXd> no_i = arrays;
  no_i.erase("i");
  EXPECT_NE(ExpectInvalid([&] { RecordedJointLogFromArrays(no_i, puma, "<arrays>", format, TorqueColumns::kRequired); })
                .find("drive_gains given but there is no array 'i'"),
            std::string::npos);
  format.angle_unit = "rad";  // 10 rad is outside joint 2's limits
  EXPECT_NE(ExpectInvalid([&] { RecordedJointLogFromArrays(arrays, puma, "<arrays>", format, TorqueColumns::kRequired); })
                .find("<arrays>: q: row 0, joint 2: 10 rad is outside the joint's limits"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench
