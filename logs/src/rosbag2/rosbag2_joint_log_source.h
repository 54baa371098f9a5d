// The JointLogSource over a rosbag2 bag's JointState topic
// (idbench/logs/rosbag2_joint_log.h says what it reads and throws).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "bag_files.h"
#include "bag_message_reader.h"
#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"
#include "joint_state_message.h"

namespace idbench::internal {

class Rosbag2JointLogSource final : public JointLogSource {
 public:
  // Picks the topic and reads the bag once to check every message.
  Rosbag2JointLogSource(const std::string& path, const RobotModel& model, const JointLogFormat& format,
                        TorqueColumns torques);
  const JointLogLayout& layout() const override { return layout_; }
  bool Next(Eigen::Index max_samples, JointLogChunk* chunk) override;
  void Rewind() override;

 private:
  // The joint state the source hands out for one message.
  struct Sample {
    // Times in integer nanoseconds: a double holds 1.7e9 s only to 2.4e-7 s,
    // so t is formed from the difference to the first message's time.
    std::int64_t stamp_ns = 0;    // header.stamp [ns since the epoch]; 0 when not stamped
    std::int64_t receive_ns = 0;  // the bag's log time [ns since the epoch]
    Eigen::VectorXd q, qd, tau;  // per model joint; qd, tau left as they were when the message lacks them
    bool has_velocity = false, has_effort = false;
  };
  std::string ChooseTopic(const std::string& requested) const;
  // Reads the next message of the topic (across the bag's files) into
  // message_; false after the last one.
  bool ReadMessage();
  // message_ as a sample of the model's joints: joints matched by name,
  // positions converted and checked against the limits.
  void ToSample(Sample* sample);
  [[noreturn]] void Fail(const std::string& what) const;  // "file: message N: what (topic, record)"

  std::string path_;
  BagFiles files_;
  std::string topic_;
  std::vector<std::string> joint_names_;  // the model's, in chain order
  std::vector<JointLimits> limits_;
  double to_rad_ = 1.0;
  bool use_stamps_ = true;
  std::int64_t t0_ns_ = 0;  // the first message's time (stamp or receive time) [ns]: t = 0 there

  // Where the reading stands.
  std::unique_ptr<BagMessageReader> reader_;
  std::size_t file_index_ = 0;
  std::int64_t message_index_ = -1;  // of message_
  std::int64_t n_messages_ = 0;      // of the topic, counted when opened
  std::int64_t handed_out_ = 0;
  BagMessage raw_;
  JointStateMessage message_;
  Sample sample_;

  // The name → joint mapping, kept while messages list the same names.
  std::vector<std::string> mapped_names_;
  std::vector<int> slot_;  // per model joint: its index in message_.name
  std::vector<std::string> ignored_names_;  // names that are not the model's joints, each once

  JointLogLayout layout_;
};

}  // namespace idbench::internal
