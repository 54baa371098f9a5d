#include "idbench/logs/open_joint_log.h"

#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_description.h"
#include "idbench/logs/rosbag2_joint_log.h"

#include <stdexcept>

namespace idbench {

std::unique_ptr<JointLogSource> OpenJointLog(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques) {
  // A rosbag2 bag: a directory with metadata.yaml, a .db3 or an .mcap file.
  if (IsRosbag2Path(path)) return OpenRosbag2JointLog(path, model, format, torques);
  if (!format.topic.empty()) throw std::invalid_argument(path + ": topic: '" + format.topic + "' given, but only a bag has topics");
  // A log description (.json, .yaml, .yml): the files it describes.
  if (IsJointLogDescriptionPath(path)) {
    return OpenDescribedJointLog(ReadJointLogDescription(path), model, format, torques);
  }
  // A CSV file, streamed.
  return OpenJointLogCsv(path, model, format, torques);
}

}  // namespace idbench
