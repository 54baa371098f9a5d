// sensor_msgs/msg/JointState as a bag stores it (CDR), decoded by hand:
//   std_msgs/Header header (builtin_interfaces/Time stamp {int32 sec,
//   uint32 nanosec}, string frame_id), string[] name, float64[] position,
//   float64[] velocity, float64[] effort.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace idbench::internal {

inline constexpr char kJointStateType[] = "sensor_msgs/msg/JointState";

struct JointStateMessage {
  std::int32_t stamp_sec = 0;       // header.stamp [s]
  std::uint32_t stamp_nanosec = 0;  // header.stamp [ns], below 1e9
  std::string frame_id;
  std::vector<std::string> name;  // joint names, in any order
  // Per name, or empty when not recorded.
  std::vector<double> position;  // [rad]
  std::vector<double> velocity;  // [rad/s]
  std::vector<double> effort;    // [N m]
};

// Decodes one CDR message into *message, reusing its storage (no allocation
// once the vectors have grown to the message's size). Throws
// std::invalid_argument naming the field for a malformed message: an item
// overrunning the bytes, or position, velocity, effort neither empty nor of
// name's length ("position has 5 entries, name has 7"). Trailing bytes (the
// padding some writers add) are ignored.
void DecodeJointState(const std::uint8_t* data, std::size_t size, JointStateMessage* message);

}  // namespace idbench::internal
