#include "joint_state_message.h"

#include <stdexcept>

#include "cdr_reader.h"

namespace idbench::internal {

void DecodeJointState(const std::uint8_t* data, std::size_t size, JointStateMessage* message) {
  CdrReader cdr(data, size);
  message->stamp_sec = cdr.ReadInt32("header.stamp.sec");
  message->stamp_nanosec = cdr.ReadUint32("header.stamp.nanosec");
  cdr.ReadString("header.frame_id", &message->frame_id);
  cdr.ReadStringSequence("name", &message->name);
  cdr.ReadFloat64Sequence("position", &message->position);
  cdr.ReadFloat64Sequence("velocity", &message->velocity);
  cdr.ReadFloat64Sequence("effort", &message->effort);

  // Each array is per joint name, or empty (not recorded).
  const std::size_t n = message->name.size();
  for (const auto& [field, values] : {std::pair<const char*, const std::vector<double>*>{"position", &message->position},
                                      {"velocity", &message->velocity},
                                      {"effort", &message->effort}}) {
    if (!values->empty() && values->size() != n) {
      throw std::invalid_argument(std::string(field) + " has " + std::to_string(values->size()) +
                                  " entries, name has " + std::to_string(n));
    }
  }
}

}  // namespace idbench::internal
