// A log description (docs/formats/joint-logs.md, "Log descriptions"): one
// JSON or YAML file saying how a log is laid out, so that logs idbench's CSV
// does not fit (several files, no time column, one number per line) are read
// wherever a log is:
//   {"rate": 5000,
//    "files": [{"path": "pos.csv", "columns": "q1..q6"},
//              {"path": "tau.txt", "layout": "one-value-per-line", "stride": 6, "columns": "tau1..tau6"}],
//    "time_window": [0.5, 8.5], "angle_unit": "rad", "drive_gains": [...],
//    "transmission": {"reduction": [32, 32, 45, -48, 45, 32]}}
// With a transmission, actuator-side columns (qm*, qdm*, taum*, im*) are read
// and mapped to the joint side (JointLogFormat::transmission).
// The files are joined sample by sample (same number of samples each).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"

namespace idbench {

// One file of a described log.
struct JointLogFileDescription {
  enum class Layout { kCsv, kOneValuePerLine };
  std::string path;                   // relative to the description's folder, or absolute
  Layout layout = Layout::kCsv;       // "csv" or "one-value-per-line"
  int stride = 0;                     // one-value-per-line: lines per sample, the number of columns
  std::vector<std::string> columns;   // as JointLogFormat::columns; empty (CSV only): the file's header names them
  int skip = 0;                       // lines skipped at the start of the file (a title, comments)
};

struct JointLogDescription {
  std::string source;                 // the description file, for messages and relative paths
  std::optional<double> rate_hz;      // [Hz] t = k / rate for logs without a t column (k from 0)
  std::vector<JointLogFileDescription> files;
  std::vector<double> time_window;    // {T0, T1} [s]; empty: the whole log
  std::optional<std::string> angle_unit;  // "rad" or "deg"
  std::vector<double> drive_gains;    // [N m/A] τ = K·i, one per joint (per motor for im*)
  // {"reduction": [N1, ...]} (A = diag(N)) or {"actuator_from_joint": [[...], ...]},
  // either with "joint_offset": [q0_1, ...] [rad]; its source names the description.
  std::optional<Transmission> transmission;

  static constexpr int kMaxFiles = 16;
  static constexpr int kMaxStride = JointLogFormat::kMaxColumns;
  static constexpr int kMaxSkip = 1'000'000;
  // [Hz] A log for identification is sampled at 100 Hz to 10 kHz; below 1 Hz
  // the filters' cutoffs and the resampling grid lose their meaning.
  static constexpr double kMinRateHz = 1.0;
  static constexpr double kMaxRateHz = 1e6;
  static constexpr int kMaxBytes = 1 << 20;  // a description is a few lines
};

// Whether `path` names a description (.json, .yaml, .yml).
bool IsJointLogDescriptionPath(const std::string& path);

// Parses a description (YAML when `yaml`, else JSON). Unknown keys, wrong
// types and values out of bounds throw std::invalid_argument "source: .files[1].stride:
// what" (jq-style paths); a syntax error names the line.
JointLogDescription ParseJointLogDescription(const std::string& text, const std::string& source, bool yaml);
// A transmission alone (a description's "transmission" object as the whole
// text: {"reduction": [...]} or {"actuator_from_joint": [[...], ...]}, with
// an optional "joint_offset"), checked as in a description; fields are named
// from the text's own top (".reduction[2]"), syntax errors at their line.
Transmission ParseTransmissionText(const std::string& text, const std::string& source, bool yaml);
// Reads one, YAML or JSON by its extension.
JointLogDescription ReadJointLogDescription(const std::string& path);

// The described log for `model` as one source. `format` is the caller's
// (options): it must not name columns (the description's files do), and its
// angle unit (when not the default rad) and drive gains must not be given in
// both; the description's fill them otherwise. layout().time_window is the
// description's. Throws std::invalid_argument naming the description and the
// field, or the data file and line.
std::unique_ptr<JointLogSource> OpenDescribedJointLog(const JointLogDescription& description, const RobotModel& model,
                                                      const JointLogFormat& format, TorqueColumns torques);

}  // namespace idbench
