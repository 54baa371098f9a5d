#include "idbench/logs/open_joint_log.h"

#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_description.h"
#include "idbench/logs/rosbag2_joint_log.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "column_names.h"
#include "held_torque_source.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"

namespace idbench {

namespace {

std::unique_ptr<JointLogSource> OpenJointLogAsRecorded(const std::string& path, const RobotModel& model,
                                                       const JointLogFormat& format, TorqueColumns torques) {
  // A rosbag2 bag: a directory with metadata.yaml, a .db3 or an .mcap file
  // (any other directory is refused there, saying it lacks metadata.yaml).
  std::error_code error;
  if (IsRosbag2Path(path) || std::filesystem::is_directory(path, error)) {
    return OpenRosbag2JointLog(path, model, format, torques);
  }
  if (!format.topic.empty()) throw std::invalid_argument(path + ": topic: '" + format.topic + "' given, but only a bag has topics");
  // A log description (.json, .yaml, .yml): the files it describes.
  if (IsJointLogDescriptionPath(path)) {
    return OpenDescribedJointLog(ReadJointLogDescription(path), model, format, torques);
  }
  // A CSV file, streamed.
  return OpenJointLogCsv(path, model, format, torques);
}

}  // namespace

std::unique_ptr<JointLogSource> OpenJointLog(const std::string& path, const RobotModel& model,
                                             const JointLogFormat& format, TorqueColumns torques) {
  std::unique_ptr<JointLogSource> source = OpenJointLogAsRecorded(path, model, format, torques);
  if (!format.torque_held) return source;
  return std::make_unique<internal::HeldTorqueSource>(std::move(source));
}

namespace {

// A header field that names a torque or current column, joint or motor side:
// tau3, i3, taum3, im3, tau.<joint>, i.<joint>, ... (quotes and spaces around it ignored).
bool IsTorqueOrCurrentColumn(std::string field) {
  const size_t begin = field.find_first_not_of(" \t\"\r"), end = field.find_last_not_of(" \t\"\r");
  if (begin == std::string::npos) return false;
  field = field.substr(begin, end - begin + 1);
  const std::string prefix = field.substr(0, field.find('.'));
  if (prefix != field) return prefix == "tau" || prefix == "i" || prefix == "taum" || prefix == "im";
  internal::ColumnTarget target{};
  if (internal::ParseColumnName(field, &target) || internal::ParseActuatorColumnName(field, &target)) {
    return target.kind == 4 || target.kind == 5;
  }
  return false;
}

}  // namespace

bool IsRecordedJointLogPath(const std::string& path) {
  std::error_code error;
  if (IsRosbag2Path(path) || std::filesystem::is_directory(path, error)) return true;  // a folder is only ever a bag
  if (path.ends_with(".yaml") || path.ends_with(".yml")) return true;
  try {
    if (path.ends_with(".json")) {
      const nlohmann::json j = ParseJsonInput(ReadInputFile(path), path);
      return j.is_object() && j.contains("files");
    }
    if (!path.ends_with(".csv")) return false;
    CheckInputFile(path);  // a regular file within bounds: a FIFO would block
    std::ifstream in(path);
    std::string line(MaxLineBytes(), '\0');
    in.getline(line.data(), static_cast<std::streamsize>(line.size()));
    line.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount() - (in.eof() ? 0 : 1), 0)));
    for (size_t at = 0; at <= line.size();) {
      const size_t comma = std::min(line.find(',', at), line.size());
      if (IsTorqueOrCurrentColumn(line.substr(at, comma - at))) return true;
      at = comma + 1;
    }
  } catch (const std::invalid_argument&) {
  }
  return false;
}

}  // namespace idbench
