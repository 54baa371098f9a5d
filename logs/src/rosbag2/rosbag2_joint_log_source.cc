#include "rosbag2_joint_log_source.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "idbench/logs/rosbag2_joint_log.h"

namespace idbench {
namespace internal {
namespace {

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// t [s] of a time `ns` after `t0_ns` (both [ns], ns >= t0_ns): the exact
// integer difference (unsigned, so any two int64 times subtract without
// overflow), divided by 1e9 once, so k ms gives the double nearest k/1000 s,
// as a CSV's "0.00k" parses.
double SecondsSince(std::int64_t t0_ns, std::int64_t ns) {
  return static_cast<double>(static_cast<std::uint64_t>(ns) - static_cast<std::uint64_t>(t0_ns)) / 1e9;
}

}  // namespace

Rosbag2JointLogSource::Rosbag2JointLogSource(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques)
    : path_(path), files_(FindBagFiles(path)) {
  // Options that belong to column files.
  if (!format.columns.empty()) {
    throw std::invalid_argument(path + ": columns: a rosbag2 bag's JointState names its joints; columns do not apply");
  }
  if (!format.drive_gains.empty()) {
    throw std::invalid_argument(path + ": drive_gains: a JointState's effort is a joint torque; a bag has no currents");
  }
  if (torques == TorqueColumns::kCurrents) {
    throw std::invalid_argument(path + ": a JointState has no motor currents (i), which the drive gains need");
  }
  if (format.angle_unit != "rad" && format.angle_unit != "deg") {
    throw std::invalid_argument(path + ": angle_unit '" + format.angle_unit + "', expected rad or deg");
  }
  to_rad_ = format.degrees() ? std::numbers::pi / 180.0 : 1.0;
  for (const Link& link : model.links()) {
    joint_names_.push_back(link.joint_name);
    limits_.push_back(link.limits);
  }
  const int n_dof = model.n_dof();
  sample_.q.resize(n_dof);
  sample_.qd.resize(n_dof);
  sample_.tau.resize(n_dof);
  topic_ = ChooseTopic(format.topic);

  // One pass over the topic: every message decodes and has the model's
  // joints; which fields every message has; which clock increases.
  Rewind();
  std::int64_t unstamped = -1, no_velocity = -1, no_effort = -1;
  std::int64_t stamp_not_increasing = -1, receive_not_increasing = -1;
  std::int64_t first_stamp = 0, first_receive = 0, last_stamp = 0, last_receive = 0;
  while (ReadMessage()) {
    ToSample(&sample_);
    const std::int64_t k = message_index_;
    if (k == 0) {
      first_stamp = sample_.stamp_ns;
      first_receive = sample_.receive_ns;
    }
    if (unstamped < 0 && sample_.stamp_ns == 0) unstamped = k;
    if (no_velocity < 0 && !sample_.has_velocity) no_velocity = k;
    if (no_effort < 0 && !sample_.has_effort) no_effort = k;
    if (k > 0 && stamp_not_increasing < 0 && !(sample_.stamp_ns > last_stamp)) stamp_not_increasing = k;
    if (k > 0 && receive_not_increasing < 0 && !(sample_.receive_ns > last_receive)) receive_not_increasing = k;
    last_stamp = sample_.stamp_ns;
    last_receive = sample_.receive_ns;
  }
  n_messages_ = message_index_ + 1;
  if (n_messages_ == 0) throw std::invalid_argument(path + ": " + topic_ + " has no messages");
  if (torques == TorqueColumns::kRequired && no_effort >= 0) {
    message_index_ = no_effort;
    Fail("effort is empty, and identification needs the joint torques");
  }
  use_stamps_ = unstamped < 0;
  t0_ns_ = use_stamps_ ? first_stamp : first_receive;
  const std::int64_t not_increasing = use_stamps_ ? stamp_not_increasing : receive_not_increasing;
  if (not_increasing >= 0) {
    message_index_ = not_increasing;
    raw_ = BagMessage();
    Fail(std::string(use_stamps_ ? "header.stamp" : "receive time") + " does not increase");
  }

  // What the source holds, and notes on how it was read.
  layout_.source = path;
  layout_.n_dof = n_dof;
  layout_.has_qd = no_velocity < 0;
  layout_.has_tau = no_effort < 0;
  layout_.record_name = "message";
  layout_.notes.push_back(path + ": " + topic_ + " (" + kJointStateType + "), " +
                          std::to_string(n_messages_) + " messages; joints matched by name");
  if (!ignored_names_.empty()) {
    layout_.notes.push_back(path + ": ignored joints that the robot does not have: " + Join(ignored_names_));
  }
  layout_.notes.push_back(path + ": time from " +
                          (use_stamps_ ? std::string("header.stamp")
                                       : "the bag's receive time (header.stamp is zero in message " +
                                             std::to_string(unstamped) + ")"));
  if (!layout_.has_qd) {
    layout_.notes.push_back(path + ": message " + std::to_string(no_velocity) +
                            " has no velocity: qd is estimated from q");
  }
  Rewind();
}

std::string Rosbag2JointLogSource::ChooseTopic(const std::string& requested) const {
  // Topics of every file of the bag, each once.
  std::vector<BagTopic> topics;
  for (const std::string& file : files_.paths) {
    const std::unique_ptr<BagMessageReader> reader = OpenBagFile(files_.storage, file);
    for (const BagTopic& topic : reader->topics()) {
      if (std::none_of(topics.begin(), topics.end(), [&](const BagTopic& t) { return t.name == topic.name; })) {
        topics.push_back(topic);
      }
    }
  }
  std::vector<std::string> all, joint_states;
  for (const BagTopic& topic : topics) {
    all.push_back(topic.name + " (" + (topic.type.empty() ? "no type" : topic.type) + ")");
    if (topic.type == kJointStateType) joint_states.push_back(topic.name);
  }
  if (!requested.empty()) {
    const auto found = std::find_if(topics.begin(), topics.end(), [&](const BagTopic& t) { return t.name == requested; });
    if (found == topics.end()) {
      throw std::invalid_argument(path_ + ": topic: '" + requested + "' is not in the bag (topics: " + Join(all) + ")");
    }
    if (found->type != kJointStateType) {
      throw std::invalid_argument(path_ + ": topic: '" + requested + "' has type " + found->type + ", expected " +
                                  kJointStateType);
    }
    if (!found->serialization.empty() && found->serialization != "cdr") {
      throw std::invalid_argument(path_ + ": topic: '" + requested + "' is serialized as " + found->serialization +
                                  ", expected cdr");
    }
    return requested;
  }
  if (joint_states.empty()) {
    throw std::invalid_argument(path_ + ": no " + kJointStateType + " in the bag (topics: " + Join(all) + ")");
  }
  if (joint_states.size() > 1) {
    throw std::invalid_argument(path_ + ": several " + kJointStateType + " topics: " + Join(joint_states) +
                                "; choose one with the log format's topic");
  }
  return ChooseTopic(joint_states.front());
}

void Rosbag2JointLogSource::Rewind() {
  reader_.reset();
  file_index_ = 0;
  message_index_ = -1;
  handed_out_ = 0;
}

bool Rosbag2JointLogSource::ReadMessage() {
  while (file_index_ < files_.paths.size()) {
    if (reader_ == nullptr) {
      reader_ = OpenBagFile(files_.storage, files_.paths[file_index_]);
      reader_->Select(topic_);
    }
    bool got = false;
    try {
      got = reader_->Next(&raw_);
    } catch (const std::invalid_argument& e) {
      ++message_index_;
      raw_ = BagMessage();
      Fail(e.what());
    }
    if (got) {
      ++message_index_;
      try {
        DecodeJointState(raw_.data, raw_.size, &message_);
      } catch (const std::invalid_argument& e) {
        Fail(e.what());
      }
      return true;
    }
    reader_.reset();
    ++file_index_;
  }
  return false;
}

void Rosbag2JointLogSource::ToSample(Sample* sample) {
  // Match the names to the model's joints when they differ from the last
  // message's (most bags list the same names in every message).
  if (message_.name != mapped_names_) {
    const int n_dof = static_cast<int>(joint_names_.size());
    slot_.assign(static_cast<std::size_t>(n_dof), -1);
    for (int i = 0; i < static_cast<int>(message_.name.size()); ++i) {
      const std::string& name = message_.name[static_cast<std::size_t>(i)];
      const auto joint = std::find(joint_names_.begin(), joint_names_.end(), name);
      if (joint == joint_names_.end()) {
        if (std::find(ignored_names_.begin(), ignored_names_.end(), name) == ignored_names_.end() &&
            ignored_names_.size() < 64) {
          ignored_names_.push_back(name);
        }
        continue;
      }
      int& slot = slot_[static_cast<std::size_t>(joint - joint_names_.begin())];
      if (slot >= 0) Fail("joint '" + name + "' is named twice");
      slot = i;
    }
    for (int j = 0; j < n_dof; ++j) {
      if (slot_[static_cast<std::size_t>(j)] < 0) {
        Fail("joint '" + joint_names_[static_cast<std::size_t>(j)] + "' of the robot is missing (names: " +
             Join(message_.name) + ")");
      }
    }
    mapped_names_ = message_.name;
  }
  if (message_.position.empty()) Fail("position is empty");

  // Times, and the values of the model's joints.
  sample->stamp_ns = std::int64_t{message_.stamp_sec} * 1'000'000'000 + std::int64_t{message_.stamp_nanosec};
  sample->receive_ns = raw_.log_time_ns;
  sample->has_velocity = !message_.velocity.empty();
  sample->has_effort = !message_.effort.empty();
  for (std::size_t j = 0; j < slot_.size(); ++j) {
    const auto i = static_cast<std::size_t>(slot_[j]);
    const std::string& joint = joint_names_[j];
    const double q = message_.position[i] * to_rad_;
    if (!std::isfinite(q)) Fail("position of joint '" + joint + "' is not finite");
    if (q < limits_[j].q_min || q > limits_[j].q_max) {
      Fail("position of joint '" + joint + "' " + std::to_string(q) + " rad is outside its limits [" +
           std::to_string(limits_[j].q_min) + ", " + std::to_string(limits_[j].q_max) + "] rad");
    }
    sample->q[static_cast<Eigen::Index>(j)] = q;
    if (sample->has_velocity) {
      sample->qd[static_cast<Eigen::Index>(j)] = message_.velocity[i] * to_rad_;
      if (!std::isfinite(message_.velocity[i])) Fail("velocity of joint '" + joint + "' is not finite");
    }
    if (sample->has_effort) {
      sample->tau[static_cast<Eigen::Index>(j)] = message_.effort[i];
      if (!std::isfinite(message_.effort[i])) Fail("effort of joint '" + joint + "' is not finite");
    }
  }
}

void Rosbag2JointLogSource::Fail(const std::string& what) const {
  const std::string file = file_index_ < files_.paths.size() ? files_.paths[file_index_] : path_;
  const std::string record = reader_ != nullptr && raw_.data != nullptr ? ", " + reader_->LastRecord() : "";
  throw std::invalid_argument(file + ": message " + std::to_string(message_index_) + ": " + what + " (on " + topic_ +
                              record + ")");
}

bool Rosbag2JointLogSource::Next(Eigen::Index max_samples, JointLogChunk* chunk) {
  if (max_samples < 1) throw std::invalid_argument("JointLogSource::Next: max_samples must be at least 1");
  const Eigen::Index count = std::min<Eigen::Index>(max_samples, n_messages_ - handed_out_);
  const Eigen::Index n_dof = layout_.n_dof;
  JointLog& out = chunk->samples;
  out.t.resize(count);
  out.q.resize(count, n_dof);
  out.qd.resize(layout_.has_qd ? count : 0, layout_.has_qd ? n_dof : 0);
  out.qdd.resize(0, 0);
  out.tau.resize(layout_.has_tau ? count : 0, layout_.has_tau ? n_dof : 0);
  chunk->records.resize(static_cast<std::size_t>(count));
  for (Eigen::Index k = 0; k < count; ++k) {
    if (!ReadMessage()) throw std::invalid_argument(path_ + ": the bag ended early (was it changed while read?)");
    ToSample(&sample_);
    out.t[k] = SecondsSince(t0_ns_, use_stamps_ ? sample_.stamp_ns : sample_.receive_ns);
    out.q.row(k) = sample_.q.transpose();
    if (layout_.has_qd) out.qd.row(k) = sample_.qd.transpose();
    if (layout_.has_tau) out.tau.row(k) = sample_.tau.transpose();
    chunk->records[static_cast<std::size_t>(k)] = message_index_;
  }
  handed_out_ += count;
  return count > 0;
}

}  // namespace internal

bool IsRosbag2Path(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::error_code error;
  if (fs::is_directory(p, error)) return fs::exists(p / "metadata.yaml", error);
  const std::string extension = p.extension().string();
  return p.filename() == "metadata.yaml" || extension == ".db3" || extension == ".mcap";
}

std::unique_ptr<JointLogSource> OpenRosbag2JointLog(const std::string& path, const RobotModel& model,
                                                    const JointLogFormat& format, TorqueColumns torques) {
  return std::make_unique<internal::Rosbag2JointLogSource>(path, model, format, torques);
}

}  // namespace idbench
