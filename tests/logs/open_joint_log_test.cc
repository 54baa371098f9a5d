// OpenJointLog's companion IsRecordedJointLogPath: a recorded log is told from
// a motion by what the path holds (a bag, a log description, a CSV headed with
// torque or current columns), as compare needs where both may be given.
#include "idbench/logs/open_joint_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "logs/rosbag2/bag_fixtures.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class RecordedJointLogPathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_open_joint_log_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

TEST_F(RecordedJointLogPathTest, CsvWithTorqueOrCurrentColumnsIsALog) {
  EXPECT_TRUE(IsRecordedJointLogPath(Write("a.csv", "t,q1,qd1,qdd1,tau1\n0,0,0,0,0\n")));
  EXPECT_TRUE(IsRecordedJointLogPath(Write("b.csv", "t,q1,i1\n0,0,0\n")));
  EXPECT_TRUE(IsRecordedJointLogPath(Write("c.csv", "t,qm1,taum1\n0,0,0\n")));
  EXPECT_TRUE(IsRecordedJointLogPath(Write("d.csv", "\"t\", \"q.shoulder\", \"tau.shoulder\"\r\n0,0,0\r\n")));
  EXPECT_TRUE(IsRecordedJointLogPath(Write("e.csv", "t,q1,im2\n")));
}

TEST_F(RecordedJointLogPathTest, TrajectoryCsvIsNotALog) {
  EXPECT_FALSE(IsRecordedJointLogPath(Write("m.csv", "t,q1,qd1,qdd1\n0,0,0,0\n")));
  EXPECT_FALSE(IsRecordedJointLogPath(Write("n.csv", "t,q.tau,qd.tau,qdd.tau\n0,0,0,0\n")));  // a joint named tau
  EXPECT_FALSE(IsRecordedJointLogPath(Write("o.csv", "0,0.1,0.2\n")));                      // no header
  EXPECT_FALSE(IsRecordedJointLogPath(Write("p.csv", "")));
  EXPECT_FALSE(IsRecordedJointLogPath((dir_ / "missing.csv").string()));
  EXPECT_FALSE(IsRecordedJointLogPath("general"));
}

TEST_F(RecordedJointLogPathTest, DescriptionsAndBagsAreLogs) {
  EXPECT_TRUE(IsRecordedJointLogPath(Write("log.json", R"({"rate": 100, "files": [{"path": "q.csv", "columns": "q1"}]})")));
  EXPECT_FALSE(IsRecordedJointLogPath(Write("motion.json", R"({"family": "fourier", "f0": 0.1})")));
  EXPECT_FALSE(IsRecordedJointLogPath(Write("broken.json", "{")));
  EXPECT_TRUE(IsRecordedJointLogPath(Write("log.yaml", "rate: 100\n")));
  EXPECT_TRUE(IsRecordedJointLogPath((testing::kBags / "bag_mcap").string()));
  EXPECT_TRUE(IsRecordedJointLogPath((testing::kBags / "joint_states_zstd.mcap").string()));
  // A folder without metadata.yaml too: opening it says what it lacks (issue 35 item 21).
  EXPECT_TRUE(IsRecordedJointLogPath(dir_.string()));
}

}  // namespace
}  // namespace idbench
