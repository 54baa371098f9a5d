#include "idbench/logs/joint_log_csv_reader.h"

#include <stdexcept>
#include <utility>

#include "csv_fields.h"
#include "idbench/logs/recorded_joint_log_source.h"
#include "line_reader.h"
#include "log_columns.h"
#include "table_log_source.h"

namespace idbench {
namespace {

using internal::ColumnMessages;
using internal::LineReader;
using internal::LogPart;
using internal::TableLogSource;

// The CSV log read through `lines`: its first line (a header, or data when the
// columns list names the columns), its columns checked, then a source over its
// data lines.
std::unique_ptr<JointLogSource> OpenCsvLines(LineReader lines, const RobotModel& model, const JointLogFormat& format,
                                             TorqueColumns torques) {
  const int n_dof = model.n_dof();
  std::string why;
  if (!format.IsValid(&why) || !format.IsValidFor(n_dof, &why)) throw std::invalid_argument(why);

  // The first line: a header, or data when the columns list names the columns.
  const bool named = !format.columns.empty();
  std::int64_t line_number = 0;
  const std::vector<std::string> first_fields = internal::FirstLineFields(&lines, named, 0, &line_number);
  const bool header = !internal::AllNumbers(first_fields);

  // The columns: their names, where each goes, which ones fill the log.
  TableLogSource::Options options;
  options.model = &model;
  options.format = format;
  options.torques = torques;
  options.source = lines.source();
  const ColumnMessages messages{lines.source(), named, named ? 0 : line_number, ""};
  LogPart part(std::move(lines));
  part.columns = internal::TargetsOf(
      internal::FileColumnNames(first_fields, header, model, format, messages, line_number, &options.notes), n_dof,
      messages, format.transmission.has_value());
  options.use = internal::ChooseColumns(part.columns, n_dof, format, torques, messages, &options.warnings);
  part.label = options.source;
  part.named = named;
  part.header = header;
  part.data_after = named && !header ? 0 : line_number;  // a first line of data is read again
  std::vector<LogPart> parts;
  parts.push_back(std::move(part));
  return std::make_unique<TableLogSource>(std::move(parts), std::move(options));
}

}  // namespace

std::unique_ptr<JointLogSource> OpenJointLogCsv(const std::string& path, const RobotModel& model,
                                                const JointLogFormat& format, TorqueColumns torques) {
  return OpenCsvLines(LineReader::FromFile(path), model, format, torques);
}

RecordedJointLog ParseRecordedJointLog(const std::string& text, const RobotModel& model, const std::string& source,
                                       const JointLogFormat& format, TorqueColumns torques) {
  const std::unique_ptr<JointLogSource> log = OpenCsvLines(LineReader::FromText(text, source), model, format, torques);
  return ReadWholeLog(*log);
}

RecordedJointLog ReadRecordedJointLog(const std::string& path, const RobotModel& model, const JointLogFormat& format,
                                      TorqueColumns torques) {
  const std::unique_ptr<JointLogSource> log = OpenJointLogCsv(path, model, format, torques);
  return ReadWholeLog(*log);
}

JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source,
                          TorqueColumns torques) {
  RecordedJointLog recorded = ParseRecordedJointLog(text, model, source, JointLogFormat{}, torques);
  JointLog& log = recorded.log;
  if ((log.qd.size() > 0) != (log.qdd.size() > 0)) {
    throw std::invalid_argument(source + ":" + std::to_string(recorded.lines.front() - 1) + ": column '" +
                                (log.qd.size() > 0 ? "qd1' without qdd1" : "qdd1' without qd1") +
                                ": a trajectory needs qd and qdd both or neither");
  }
  if (torques == TorqueColumns::kCurrents) log.tau.resize(0, 0);
  return std::move(log);
}

}  // namespace idbench
