// Fuzzes the joint-log CSV reader (identify --data, gains, trajectory CSVs):
// any text is a log or one std::invalid_argument, read with a header and with
// --columns, never a crash, a hang, another exception or a leak.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/logs/joint_log_csv_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const idbench::RobotModel robot = idbench::MakePuma560();
  const std::string text(reinterpret_cast<const char*>(data), size);
  idbench::JointLogFormat with_columns;
  with_columns.columns = {"t", "q1..q6", "qd1..qd6", "_", "i1..i6"};
  with_columns.drive_gains = {1, 2, 3, 4, 5, 6};
  idbench::JointLogFormat in_degrees;
  in_degrees.angle_unit = "deg";
  idbench::JointLogFormat subset;  // over a header: matched by name, renamed, or refused
  subset.columns = {"t", "q1..q6", "tau1..tau6"};
  for (const idbench::JointLogFormat& format : {idbench::JointLogFormat{}, with_columns, in_degrees, subset}) {
    try {
      idbench::ParseRecordedJointLog(text, robot, "fuzz.csv", format, idbench::TorqueColumns::kRequired);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
