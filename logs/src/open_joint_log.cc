#include "idbench/logs/open_joint_log.h"

#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/recorded_joint_log_source.h"

namespace idbench {

std::unique_ptr<JointLogSource> OpenJointLog(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques) {
  // A CSV file, read whole for now; the streaming CSV reader replaces this.
  return std::make_unique<RecordedJointLogSource>(ReadRecordedJointLog(path, model, format, torques), path,
                                                  torques == TorqueColumns::kCurrents);
}

}  // namespace idbench
