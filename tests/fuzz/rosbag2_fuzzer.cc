// Fuzzes the hand-written parts of the ROS 2 bag reader: an input that starts
// with the MCAP magic is read as an .mcap file (records, chunks, CRCs, CDR
// JointState messages), one that starts with SQLite's header as a .db3 file
// (its topics and messages tables); any input is also decoded as one CDR
// JointState.
// Either gives a log or one std::invalid_argument: never a crash, a hang,
// another exception, a leak or an allocation the bytes do not justify.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/logs/recorded_joint_log_source.h"
#include "idbench/logs/rosbag2_joint_log.h"
#include "rosbag2/joint_state_message.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const idbench::RobotModel robot = idbench::MakePuma560();
  static const std::string stem =
      (std::filesystem::temp_directory_path() / ("idbench_rosbag2_fuzz_" + std::to_string(getpid()))).string();
  idbench::internal::JointStateMessage message;
  try {
    idbench::internal::DecodeJointState(data, size, &message);
  } catch (const std::invalid_argument&) {
  }
  // An input with the MCAP magic is read as an .mcap file, one with SQLite's
  // header (16 bytes with its NUL) as a .db3 file.
  const bool mcap = size >= 8 && std::memcmp(data, "\x89MCAP0\r\n", 8) == 0;
  const bool db3 = size >= 16 && std::memcmp(data, "SQLite format 3", 16) == 0;
  if (!mcap && !db3) return 0;
  const std::string path = stem + (mcap ? ".mcap" : ".db3");
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, file);
    std::fclose(file);
    try {
      const auto source = idbench::OpenRosbag2JointLog(path, robot, {}, idbench::TorqueColumns::kOptional);
      idbench::ReadWholeLog(*source, 7);
    } catch (const std::invalid_argument&) {
    }
    std::remove(path.c_str());
  }
  return 0;
}
