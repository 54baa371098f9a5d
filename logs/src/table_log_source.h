// A joint log read from one or more text files joined sample by sample (a
// CSV file; the files of a log description), handed out in chunks: the one
// reader behind OpenJointLog, ReadRecordedJointLog and ParseRecordedJointLog.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"
#include "idbench/logs/joint_log_source.h"
#include "line_reader.h"
#include "log_columns.h"

namespace idbench::internal {

// One file of a log: its lines and columns, and how its lines make samples.
struct LogPart {
  explicit LogPart(LineReader reader) : lines(std::move(reader)) {}
  LineReader lines;
  FileColumns columns;
  std::string label;      // the file as the join's messages name it (".files[1] (curr.csv)"), or its path
  int stride = 0;         // 0: CSV, one sample per line; n >= 1: one value per line, n lines per sample
  bool named = false;     // CSV: a columns list names the columns (fields after them are ignored)
  bool header = false;    // CSV: the first line is a header
  std::int64_t data_after = 0;  // the line after which data starts (the header's, or the lines skipped)
};

// A CSV's first lines: skips `skip` lines, then blank ones; the first line
// split into fields and its number (throws "empty file" naming the path).
std::vector<std::string> FirstLineFields(LineReader* lines, bool named, std::int64_t skip, std::int64_t* line_number);

class TableLogSource final : public JointLogSource {
 public:
  struct Options {
    const RobotModel* model = nullptr;
    JointLogFormat format;        // angle unit and drive gains (columns are the parts')
    TorqueColumns torques = TorqueColumns::kRequired;
    ColumnUse use;
    std::optional<double> rate_hz;  // t = k / rate_hz when no part has a t column
    std::string source;           // the log as layout().source and its warnings name it
    std::vector<double> time_window;  // layout().time_window (a description's)
    std::vector<std::string> notes, warnings;
  };
  // The parts' columns must be checked (TargetsOf, ChooseColumns); exactly
  // one part has t, or none and a rate is given.
  TableLogSource(std::vector<LogPart> parts, Options options);

  const JointLogLayout& layout() const override { return layout_; }
  bool Next(Eigen::Index max_samples, JointLogChunk* chunk) override;
  void Rewind() override;

 private:
  // Reads part p's next sample into values_[p]; false at its end.
  bool ReadSample(size_t p, std::int64_t* line);
  // Samples [0, n) of *out from the actuator side to the joint side, then
  // the positions checked against the joint limits.
  void ToJointSide(Eigen::Index n, JointLogChunk* chunk);
  // Parses one field of part p, column c, into values_[p][c] with the checks.
  void ReadValue(size_t p, size_t c, std::string_view field, std::int64_t line);
  // The error for parts of different lengths (part p ended first or last).
  [[noreturn]] void FailLengths(const std::vector<bool>& ended);

  std::vector<LogPart> parts_;
  Options options_;
  JointLogLayout layout_;
  double to_rad_ = 1.0;
  std::vector<std::vector<double>> values_;  // per part, per column: the sample being read
  std::vector<std::string_view> fields_;     // the fields of the line being read
  std::optional<size_t> t_part_;             // the part with the t column
  std::int64_t n_read_ = 0;                  // samples handed out since the start
  double last_t_ = 0.0;
  Eigen::VectorXd q_min_, q_max_;            // each joint's range so far [rad]
  bool ended_ = false, warned_ = false;
  unsigned actuator_kinds_ = 0;              // bit `kind`: read on the actuator side, mapped through the transmission
  std::string q_source_;                     // the file with the positions, for limit messages
};

}  // namespace idbench::internal
