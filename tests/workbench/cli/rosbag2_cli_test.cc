// idbench identify on ROS 2 bags (tests/data/bags): a bag identifies to the
// same result as the CSV of the same samples (expected.csv, written from the
// fixtures' formulas), and --topic picks the topic.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "workbench/cli/cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using idbench::testing::CliFixture;
using idbench::testing::Result;
using idbench::testing::Slurp;

const fs::path kBags = fs::path(IDBENCH_SOURCE_DIR) / "tests" / "data" / "bags";

class Rosbag2CliTest : public CliFixture {
 protected:
  Result Identify(const std::string& data, const std::string& out, const std::string& more = "") {
    return Run("identify --robot puma560 --estimator ols --data " + data + " --out " + (dir_ / out).string() + " " +
               more);
  }
  nlohmann::json Json(const std::string& out) {
    nlohmann::json j = nlohmann::json::parse(Slurp(dir_ / out / "identified.json"));
    for (const char* key : {"command", "data", "log_preparation"}) j.erase(key);  // they name the file
    return j;
  }
};

// 200 samples (2 s) identify all the way to the verdict; the result is the
// CSV's, number for number (the bag's values are the CSV's bit for bit).
TEST_F(Rosbag2CliTest, ABagIdentifiesAsTheSameLogInCsv) {
  const Result csv = Identify((kBags / "expected.csv").string(), "csv");
  ASSERT_TRUE(fs::exists(dir_ / "csv" / "identified.json")) << csv.err;
  for (const char* bag : {"bag_db3", "bag_mcap", "joint_states_lz4.mcap"}) {
    const Result r = Identify((kBags / bag).string(), bag);
    EXPECT_EQ(r.exit_code, csv.exit_code) << r.err;
    EXPECT_EQ(r.err.find(bag), std::string::npos) << "an error about the bag: " << r.err;
    EXPECT_NE(r.out.find("/joint_states (sensor_msgs/msg/JointState), 200 messages"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ignored joints that the robot does not have: gripper_finger_joint"), std::string::npos);
    EXPECT_NE(r.out.find("time from header.stamp"), std::string::npos);
    ASSERT_TRUE(fs::exists(dir_ / bag / "identified.json")) << r.err;
    const nlohmann::json j = Json(bag);
    // 200 read at 100 Hz; qdd by filtering at 10 Hz drops 5/10 Hz = 50 samples at each end: 100 in the fit.
    EXPECT_EQ(j["n_samples_read"].get<int>(), 200);
    EXPECT_EQ(j["n_samples"].get<int>(), 100);
    EXPECT_TRUE(j == Json("csv")) << bag << " identifies otherwise than expected.csv";
  }
}

TEST_F(Rosbag2CliTest, TopicPicksTheJointStateTopic) {
  const Result ok = Identify((kBags / "bag_db3").string(), "ok", "--topic /joint_states");
  EXPECT_TRUE(fs::exists(dir_ / "ok" / "identified.json")) << ok.err;
  const Result other = Identify((kBags / "bag_db3").string(), "other", "--topic /other");
  EXPECT_NE(other.exit_code, 0);
  EXPECT_NE(other.err.find("--topic: '/other' has type std_msgs/msg/String, expected sensor_msgs/msg/JointState"),
            std::string::npos)
      << other.err;
  const Result csv = Identify((kBags / "expected.csv").string(), "csv", "--topic /joint_states");
  EXPECT_NE(csv.exit_code, 0);
  EXPECT_NE(csv.err.find("--topic: '/joint_states' given, but only a bag has topics"), std::string::npos) << csv.err;
}

TEST_F(Rosbag2CliTest, ADamagedBagIsOneErrorNamingTheMessage) {
  const Result r = Identify((kBags / "ragged.mcap").string(), "ragged");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("ragged.mcap: message 57: position has 5 entries, name has 7"), std::string::npos) << r.err;
}

}  // namespace
