// rosbag2 bags read as joint logs, against the fixtures' truth
// (tests/data/bags/README.md): expected.csv holds the 200 samples every good
// bag encodes (written by make_db3.py from formulas, the MCAP files by npm's
// @mcap/core), so each format must reproduce it exactly; each damaged bag must
// be refused naming its file, the message and what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/puma560.h"
#include "idbench/logs/open_joint_log.h"
#include "idbench/logs/recorded_joint_log_source.h"
#include "idbench/logs/rosbag2_joint_log.h"
#include "logs/rosbag2/bag_fixtures.h"

namespace idbench {
namespace {

using testing::kBags;

std::string Bag(const std::string& name) { return (kBags / name).string(); }

// expected.csv: t, q1..q6, qd1..qd6, tau1..tau6, 200 rows.
JointLog Expected() {
  std::ifstream in(kBags / "expected.csv");
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::vector<double> row;
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  JointLog log;
  const auto n = static_cast<Eigen::Index>(rows.size());
  log.t.resize(n);
  log.q.resize(n, 6);
  log.qd.resize(n, 6);
  log.tau.resize(n, 6);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::vector<double>& row = rows[static_cast<size_t>(k)];
    log.t[k] = row[0];
    for (int j = 0; j < 6; ++j) {
      log.q(k, j) = row[static_cast<size_t>(1 + j)];
      log.qd(k, j) = row[static_cast<size_t>(7 + j)];
      log.tau(k, j) = row[static_cast<size_t>(13 + j)];
    }
  }
  return log;
}

RecordedJointLog Read(const std::string& path, Eigen::Index chunk = 65536, const JointLogFormat& format = {},
                      TorqueColumns torques = TorqueColumns::kRequired) {
  const RobotModel model = MakePuma560();
  const std::unique_ptr<JointLogSource> source = OpenJointLog(path, model, format, torques);
  return ReadWholeLog(*source, chunk);
}

void ExpectEqualsExpected(const RecordedJointLog& read) {
  const JointLog expected = Expected();
  ASSERT_EQ(expected.n_samples(), 200);
  ASSERT_EQ(read.log.n_samples(), 200);
  EXPECT_LE((read.log.t - expected.t).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((read.log.q - expected.q).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(read.log.qd.rows(), 200);
  EXPECT_LE((read.log.qd - expected.qd).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(read.log.qdd.size(), 0);
  ASSERT_EQ(read.log.tau.rows(), 200);
  EXPECT_LE((read.log.tau - expected.tau).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(read.lines.front(), 0);
  EXPECT_EQ(read.lines.back(), 199);
}

class Rosbag2JointLogTest : public ::testing::TestWithParam<const char*> {};

TEST_P(Rosbag2JointLogTest, ReadsTheExpectedSamples) { ExpectEqualsExpected(Read(Bag(GetParam()))); }

INSTANTIATE_TEST_SUITE_P(EveryStorage, Rosbag2JointLogTest,
                         ::testing::Values("bag_db3", "bag_db3/bag_db3_0.db3", "bag_db3/metadata.yaml",
                                           "joint_states_none.mcap", "joint_states_lz4.mcap",
                                           "joint_states_zstd.mcap", "bag_mcap"));

TEST(Rosbag2JointLogSourceTest, ChunksOfAnySizeGiveTheWholeLog) {
  for (const char* bag : {"bag_db3", "joint_states_lz4.mcap"}) {
    const RecordedJointLog whole = Read(Bag(bag), 200);
    for (const Eigen::Index chunk : {1, 7, 200}) {
      const RecordedJointLog read = Read(Bag(bag), chunk);
      EXPECT_EQ(read.log.t, whole.log.t) << bag << " chunk " << chunk;
      EXPECT_EQ(read.log.q, whole.log.q) << bag << " chunk " << chunk;
      EXPECT_EQ(read.log.qd, whole.log.qd) << bag << " chunk " << chunk;
      EXPECT_EQ(read.log.tau, whole.log.tau) << bag << " chunk " << chunk;
      EXPECT_EQ(read.lines, whole.lines) << bag << " chunk " << chunk;
    }
  }
  ExpectEqualsExpected(Read(Bag("bag_db3"), 7));
}

TEST(Rosbag2JointLogSourceTest, RewindsForASecondPassAndSaysHowItRead) {
  const RobotModel model = MakePuma560();
  const std::unique_ptr<JointLogSource> source =
      OpenRosbag2JointLog(Bag("joint_states_zstd.mcap"), model, {}, TorqueColumns::kRequired);
  const JointLogLayout& layout = source->layout();
  EXPECT_EQ(layout.n_dof, 6);
  EXPECT_TRUE(layout.has_qd);
  EXPECT_TRUE(layout.has_tau);
  EXPECT_FALSE(layout.has_qdd);
  EXPECT_EQ(layout.record_name, "message");
  std::string notes;
  for (const std::string& note : layout.notes) notes += note + "\n";
  EXPECT_NE(notes.find("/joint_states"), std::string::npos) << notes;
  EXPECT_NE(notes.find("gripper_finger_joint"), std::string::npos) << notes;
  EXPECT_NE(notes.find("header.stamp"), std::string::npos) << notes;
  JointLogChunk chunk;
  ASSERT_TRUE(source->Next(150, &chunk));
  ASSERT_TRUE(source->Next(150, &chunk));
  EXPECT_EQ(chunk.samples.n_samples(), 50);
  EXPECT_FALSE(source->Next(150, &chunk));
  EXPECT_EQ(chunk.samples.n_samples(), 0);
  source->Rewind();
  ExpectEqualsExpected(ReadWholeLog(*source, 64));
}

TEST(Rosbag2JointLogSourceTest, ChoosesTheTopicByName) {
  JointLogFormat format;
  format.topic = "/joint_states";
  ExpectEqualsExpected(Read(Bag("bag_db3"), 64, format));
  format.topic = "/other";
  EXPECT_THROW(Read(Bag("bag_db3"), 64, format), std::invalid_argument);
  format.topic = "/nowhere";
  EXPECT_THROW(Read(Bag("joint_states_none.mcap"), 64, format), std::invalid_argument);
}

// The message of what `path` throws when opened and read whole.
std::string Error(const std::string& path, const JointLogFormat& format = {},
                  TorqueColumns torques = TorqueColumns::kRequired) {
  try {
    Read(path, 64, format, torques);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

void ExpectMentions(const std::string& message, const std::vector<std::string>& parts) {
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(Rosbag2JointLogSourceTest, NamesTheFileTheMessageAndTheFault) {
  ExpectMentions(Error(Bag("bad_crc.mcap")),
                 {"bad_crc.mcap: message 10: ", "Chunk record at offset 4508", "CRC", "3126000633", "716477711"});
  ExpectMentions(Error(Bag("truncated.mcap")),
                 {"truncated.mcap: message 22: ", "unexpected end of file in Chunk record at offset 4642"});
  ExpectMentions(Error(Bag("wrong_type.mcap")),
                 {"wrong_type.mcap: ", "no sensor_msgs/msg/JointState in the bag",
                  "/joint_states (std_msgs/msg/String)"});
  ExpectMentions(Error(Bag("ragged.mcap")),
                 {"ragged.mcap: message 57: ", "position has 5 entries, name has 7", "/joint_states"});
  ExpectMentions(Error(Bag("ragged_db3")),
                 {"ragged_db3_0.db3: message 57: ", "position has 5 entries, name has 7", "messages.id 60"});
  for (const char* bag : {"missing_joint.mcap", "missing_joint_db3"}) {
    ExpectMentions(Error(Bag(bag)), {bag, ": message 0: ", "joint 'joint4' of the robot is missing", "/joint_states"});
  }
}

TEST(Rosbag2JointLogSourceTest, RefusesWhatABagCannotGive) {
  JointLogFormat format;
  format.columns = {"t", "q1..q6"};
  ExpectMentions(Error(Bag("bag_db3"), format), {"bag_db3: columns"});
  format = {};
  format.drive_gains = std::vector<double>(6, 1.0);
  ExpectMentions(Error(Bag("bag_db3"), format), {"drive_gains"});
  ExpectMentions(Error(Bag("bag_db3"), {}, TorqueColumns::kCurrents), {"no motor currents"});
  ExpectMentions(Error(Bag("no_such.mcap")), {"no_such.mcap: cannot open"});
  ExpectMentions(Error(Bag("expected.csv.mcap")), {"expected.csv.mcap"});
  format = {};
  format.topic = "/joint_states";
  ExpectMentions(Error(Bag("expected.csv"), format), {"expected.csv: topic"});
}

TEST(Rosbag2JointLogSourceTest, KnowsABagByItsPath) {
  EXPECT_TRUE(IsRosbag2Path(Bag("bag_db3")));
  EXPECT_TRUE(IsRosbag2Path(Bag("bag_mcap/metadata.yaml")));
  EXPECT_TRUE(IsRosbag2Path(Bag("ragged.mcap")));
  EXPECT_TRUE(IsRosbag2Path("anything.db3"));
  EXPECT_FALSE(IsRosbag2Path(Bag("expected.csv")));
  EXPECT_FALSE(IsRosbag2Path(kBags.string()));  // a directory without metadata.yaml
}

}  // namespace
}  // namespace idbench
