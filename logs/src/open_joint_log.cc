#include "idbench/logs/open_joint_log.h"

#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_description.h"

namespace idbench {

std::unique_ptr<JointLogSource> OpenJointLog(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques) {
  // A log description (.json, .yaml, .yml): the files it describes.
  if (IsJointLogDescriptionPath(path)) {
    return OpenDescribedJointLog(ReadJointLogDescription(path), model, format, torques);
  }
  // A CSV file, streamed.
  return OpenJointLogCsv(path, model, format, torques);
}

}  // namespace idbench
