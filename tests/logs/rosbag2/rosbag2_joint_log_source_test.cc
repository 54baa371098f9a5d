// rosbag2 bags read as joint logs, against the fixtures' truth
// (tests/data/bags/README.md): expected.csv holds the 200 samples every good
// bag encodes (written by make_db3.py from formulas, the MCAP files by npm's
// @mcap/core), so each format must reproduce it exactly; each damaged bag must
// be refused naming its file, the message and what is wrong.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
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
  // t counts from the first message's stamp (1 s in the fixtures).
  EXPECT_EQ(read.log.t[0], 0.0);
  EXPECT_LE((read.log.t.array() - (expected.t.array() - expected.t[0])).abs().maxCoeff(), 1e-12);
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
  ExpectMentions(Error(Bag("no_such.mcap")), {"no_such.mcap: cannot read the file"});
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

// Issue 35 item 11: stamps after a real epoch (sec 1.7e9) exactly 1 ms apart
// read as exactly regular, t = k / 1000 s from the first stamp, and give the
// same samples bit for bit as the same data in a CSV (make_epoch_db3.py
// writes both). sec + nanosec * 1e-9 in a double jittered every step by up to
// 1.2e-7 s and started at 1.7e9 s.
TEST(Rosbag2JointLogSourceTest, StampsAfterTheEpochKeepTheirNanoseconds) {
  const RecordedJointLog bag = Read(Bag("epoch_1ms.db3"));
  const RecordedJointLog csv = Read(Bag("epoch_1ms.csv"));
  ASSERT_EQ(bag.log.n_samples(), 200);
  for (Eigen::Index k = 0; k < 200; ++k) ASSERT_EQ(bag.log.t[k], static_cast<double>(k) / 1000.0) << k;
  EXPECT_EQ(bag.log.t, csv.log.t);
  EXPECT_EQ(bag.log.q, csv.log.q);
  EXPECT_EQ(bag.log.qd, csv.log.qd);
  EXPECT_EQ(bag.log.tau, csv.log.tau);
}

// Writes and removes a scratch folder for hostile bags.
class HostileBagTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("idbench_hostile_bag_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    std::filesystem::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::filesystem::path dir_;
};

// The message of what opening `path` as a joint log throws, within 10 s: a
// reader blocked on a FIFO is released by opening its other end (so the old
// code fails here instead of hanging).
std::string ErrorWithin10s(const std::string& path, const std::string& fifo) {
  std::future<std::string> error = std::async(std::launch::async, [path] { return Error(path); });
  if (error.wait_for(std::chrono::seconds(10)) == std::future_status::ready) return error.get();
  const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (writer >= 0) ::close(writer);
  error.wait();
  return "(blocked on the FIFO)";
}

// Issue 35 item 6: a FIFO named as a bag's file is refused at once, as a CSV's is.
TEST_F(HostileBagTest, AFifoIsRefusedNotWaitedOn) {
  for (const std::string name : {"run.mcap", "run_0.db3", "bag/metadata.yaml"}) {
    std::filesystem::create_directories((dir_ / name).parent_path());
    const std::string fifo = (dir_ / name).string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(ErrorWithin10s(fifo, fifo), fifo + ": is a FIFO (named pipe), not a regular file; pass a file");
    if (name == "bag/metadata.yaml") {  // the bag's folder
      EXPECT_EQ(ErrorWithin10s((dir_ / "bag").string(), fifo), fifo + ": is a FIFO (named pipe), not a regular file; pass a file");
    }
    std::filesystem::remove(fifo);
  }
  // A metadata.yaml naming a FIFO as its storage file.
  Write("split/metadata.yaml", "rosbag2_bagfile_information:\n  storage_identifier: mcap\n"
                               "  relative_file_paths: [split_0.mcap]\n");
  const std::string fifo = (dir_ / "split/split_0.mcap").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(ErrorWithin10s((dir_ / "split").string(), fifo),
            fifo + ": is a FIFO (named pipe), not a regular file; pass a file");
}

// Issue 35 item 13: metadata.yaml fields of the wrong kind are refused as
// invalid input (exit 2) naming the file and the field, not a bare yaml-cpp
// conversion error (exit 1).
TEST_F(HostileBagTest, MetadataFieldsOfTheWrongKindAreNamed) {
  const std::string head = "rosbag2_bagfile_information:\n";
  const std::string files = "  relative_file_paths: [bag_0.mcap]\n";
  const struct {
    std::string yaml, message;
  } cases[] = {
      {head + "  storage_identifier: {a: 1}\n" + files, "storage_identifier: expected a string, got a map"},
      {head + "  storage_identifier: [mcap]\n" + files, "storage_identifier: expected a string, got a list"},
      {head + "  storage_identifier: mcap\n  compression_format: {zstd: 1}\n" + files,
       "compression_format: expected a string, got a map"},
      {head + "  storage_identifier: mcap\n  relative_file_paths: [[bag_0.mcap]]\n",
       "relative_file_paths[0]: expected a string, got a list"},
      {head + "  storage_identifier: mcap\n  relative_file_paths: [a.mcap, {path: b.mcap}]\n",
       "relative_file_paths[1]: expected a string, got a map"},
      {head + "  storage_identifier: mcap\n  relative_file_paths: {path: b.mcap}\n",
       "relative_file_paths: expected a list of file names, got a map"},
      {head + "  storage_identifier: mcap\n  relative_file_paths: bag_0.mcap\n",
       "relative_file_paths: expected a list of file names, got 'bag_0.mcap'"},
      {head + "  storage_identifier: mcap\n  relative_file_paths: [\"\"]\n",
       "relative_file_paths[0]: expected a file name, got none"},
  };
  for (const auto& c : cases) {
    const std::string metadata = Write("bag/metadata.yaml", c.yaml);
    EXPECT_EQ(Error((dir_ / "bag").string()), metadata + ": " + c.message) << c.yaml;
  }
}

// Issue 35 item 21: a folder without metadata.yaml says so (and what it
// holds), a directory named like a storage file says it is a directory.
TEST_F(HostileBagTest, NamesAFolderWithoutMetadataAndADirectoryNamedAsAFile) {
  std::filesystem::create_directories(dir_ / "rosbag2_run");
  std::filesystem::copy_file(kBags / "joint_states_zstd.mcap", dir_ / "rosbag2_run" / "run_0.mcap");
  const std::string folder = (dir_ / "rosbag2_run").string();
  EXPECT_EQ(Error(folder), folder + ": a directory without metadata.yaml, so not a rosbag2 bag folder (it holds "
                                    "run_0.mcap: pass one of those files to read it alone)");
  ExpectEqualsExpected(Read((dir_ / "rosbag2_run" / "run_0.mcap").string()));
  std::filesystem::create_directories(dir_ / "empty");
  EXPECT_EQ(Error((dir_ / "empty").string()), (dir_ / "empty").string() +
                                                   ": a directory without metadata.yaml, so not a rosbag2 bag folder "
                                                   "(it holds no .mcap or .db3 file)");
  for (const std::string name : {"bag_0.mcap", "bag_0.db3"}) {
    std::filesystem::create_directories(dir_ / name);
    EXPECT_EQ(Error((dir_ / name).string()),
              (dir_ / name).string() + ": is a directory, not a regular file; pass a file");
  }
}

}  // namespace
}  // namespace idbench
