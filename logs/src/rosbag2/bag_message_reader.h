// One storage file of a rosbag2 bag (SQLite3 .db3 or MCAP) read as a stream
// of serialized messages of one topic, in time order, one at a time: the
// interface of rosbag2's storage plugins (has_next / read_next), narrowed to
// what the joint-log source needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace idbench::internal {

struct BagTopic {
  std::string name;  // "/joint_states"
  std::string type;  // "sensor_msgs/msg/JointState"; empty when the file does not say
  std::string serialization;  // "cdr"
};

// A message as stored; data points into the reader and stays valid until the
// next call of Next or Select.
struct BagMessage {
  std::int64_t log_time_ns = 0;  // when the recorder received it [ns since the epoch]
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

class BagMessageReader {
 public:
  virtual ~BagMessageReader() = default;
  // Every topic of the file, in the order the file lists them.
  virtual const std::vector<BagTopic>& topics() const = 0;
  // Streams `topic`'s messages from the first one on.
  virtual void Select(const std::string& topic) = 0;
  // The next message of the selected topic; false at the end. Throws
  // std::invalid_argument "what" (without the path) for a damaged file:
  // truncated, a CRC mismatch, a record that overruns its container.
  virtual bool Next(BagMessage* message) = 0;
  // Where the last message came from, for messages ("messages.id 60",
  // "Message record at offset 4726").
  virtual std::string LastRecord() const = 0;
};

}  // namespace idbench::internal
