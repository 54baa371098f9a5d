// ROS 2 bags (rosbag2) as joint logs: the sensor_msgs/msg/JointState messages
// of one topic, from a bag directory (metadata.yaml and its .db3 or .mcap
// files) or a single .db3 (SQLite3) or .mcap file, streamed message by message.
#pragma once

#include <memory>
#include <string>

#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"

namespace idbench {

// Whether `path` names a bag: a directory holding metadata.yaml, that
// metadata.yaml itself, or a file ending in .db3 or .mcap.
bool IsRosbag2Path(const std::string& path);

// The JointState messages of `path` as a log of `model`. The topic is
// format.topic, or the bag's only sensor_msgs/msg/JointState topic. Joints are
// matched by name to the model's joints (Link::joint_name), in any order,
// which may change from message to message; other names (a gripper) are
// ignored with a note. position → q (in format.angle_unit, rad by ROS
// convention), velocity → qd when every message has it, effort → tau [N m]
// (required for TorqueColumns::kRequired, else kept when every message has
// it). Time: header.stamp when every message's stamp is nonzero, else the
// bag's receive time; a note says which. t [s] counts from the first
// message's time (t = 0 there), taken as integer nanoseconds until then, so
// stamps after the epoch keep their nanoseconds. records are message indices (from
// 0, counting the topic's messages only).
// Opening reads the bag once to check it, so Next does not throw; memory
// holds one message (db3) or one chunk (MCAP), whatever the bag's length.
// Throws std::invalid_argument "path: what", or "path: message N: what"
// (with the topic and the joint where they matter), for: an unreadable or
// damaged file (truncated, a chunk CRC mismatch, a chunk's uncompressed_size
// beyond what its records can give, not a bag), a path that is not a regular
// file (a FIFO, a directory named .mcap) or a directory without metadata.yaml,
// a metadata.yaml field of the wrong kind, no or several
// JointState topics without format.topic (listing them), a topic of another
// type, a malformed message (arrays of different lengths), a joint of the
// model missing from a message, a position outside its limits or not finite,
// time not increasing, no messages, and options that do not apply to a bag
// (columns, drive_gains, motor currents).
std::unique_ptr<JointLogSource> OpenRosbag2JointLog(const std::string& path, const RobotModel& model,
                                                    const JointLogFormat& format, TorqueColumns torques);

}  // namespace idbench
