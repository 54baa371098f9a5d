// OpenDescribedJointLog (joint_log_description.h): the described files as one
// TableLogSource, with the description's options merged with the caller's.
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>

#include "csv_fields.h"
#include "idbench/logs/joint_log_description.h"
#include "line_reader.h"
#include "log_columns.h"
#include "number_format.h"
#include "table_log_source.h"

namespace idbench {
namespace {

using internal::ColumnMessages;
using internal::LineReader;
using internal::LogPart;
using internal::TableLogSource;

std::string Joined(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : ",") + Shortest(v);
  return out;
}

// The caller's options and the description's: each given in one place.
JointLogFormat MergedFormat(const JointLogDescription& description, const JointLogFormat& format,
                            std::vector<std::string>* notes) {
  const std::string& source = description.source;
  if (!format.columns.empty()) {
    throw std::invalid_argument(source + ": columns given with a log description: name each file's columns in its "
                                ".files[i].columns instead");
  }
  JointLogFormat merged = format;
  if (description.angle_unit) {
    // The default (rad) cannot be told from an option given as rad.
    if (format.angle_unit != "rad") {
      throw std::invalid_argument(source + ": .angle_unit (" + *description.angle_unit + ") and the option angle_unit (" +
                                  format.angle_unit + ") both give the angle unit: give it in one place");
    }
    merged.angle_unit = *description.angle_unit;
  }
  if (!description.drive_gains.empty()) {
    if (!format.drive_gains.empty()) {
      throw std::invalid_argument(source + ": .drive_gains (" + Joined(description.drive_gains) +
                                  ") and the option drive_gains (" + Joined(format.drive_gains) +
                                  ") both give the drive gains: give them in one place");
    }
    merged.drive_gains = description.drive_gains;
  }
  if (description.transmission) {
    // The description's transmission wins over the robot's (its URDF's).
    if (format.transmission) {
      notes->push_back(source + ": .transmission used, not the one of " + format.transmission->source);
    }
    merged.transmission = description.transmission;
  }
  return merged;
}

// File i of the description, opened and its columns read and checked.
LogPart OpenPart(const JointLogDescription& description, size_t i, const RobotModel& model, const JointLogFormat& format,
                 std::vector<std::string>* notes) {
  const JointLogFileDescription& file = description.files[i];
  const std::filesystem::path relative(file.path);
  const std::string path = relative.is_absolute()
                               ? file.path
                               : (std::filesystem::path(description.source).parent_path() / relative).string();
  const std::string field = ".files[" + std::to_string(i) + "]";
  // The folder a relative path is taken in, made absolute for the message
  // ("d.json" given from the current folder; an error leaves it as given).
  std::error_code error;
  const std::filesystem::path parent = std::filesystem::path(description.source).parent_path();
  const std::filesystem::path absolute = std::filesystem::absolute(parent.empty() ? "." : parent, error);
  std::string folder = relative.is_absolute() ? ""
                       : error                ? parent.string()
                                              : absolute.lexically_normal().string();
  if (folder.size() > 1 && folder.back() == '/') folder.pop_back();  // "/cwd/." normalises to "/cwd/"
  // A file that cannot be read: the description's field names it, and the
  // folder a relative path was taken in (a symlinked description's own).
  std::optional<LogPart> opened;
  try {
    opened.emplace(LineReader::FromFile(path));
  } catch (const std::invalid_argument& e) {
    std::string why = e.what();  // "path: why"
    if (why.starts_with(path + ": ")) why = why.substr(path.size() + 2);
    throw std::invalid_argument(description.source + ": " + field + ".path: '" + file.path + "'" +
                                (folder.empty() ? "" : ", taken in the description's folder " + folder) + ": " + why);
  }
  LogPart part = std::move(*opened);
  // Lines to skip must leave some: past the end the count is wrong (not the file empty).
  if (file.skip > 0) {
    std::string_view line;
    while (part.lines.line_number() < file.skip && part.lines.Next(&line)) {
    }
    if (part.lines.line_number() < file.skip || !part.lines.Next(&line)) {
      throw std::invalid_argument(description.source + ": " + field + ".skip: skips " + std::to_string(file.skip) +
                                  " lines, but " + path + " has " + std::to_string(part.lines.line_number()) +
                                  ": nothing is left to read");
    }
    part.lines.Rewind();
  }
  part.label = field + " (" + file.path + ")";
  part.named = !file.columns.empty();
  const ColumnMessages messages{path, part.named, 0, description.source + ": " + field + ".columns"};
  JointLogFormat columns_format = format;
  columns_format.columns = file.columns;
  if (file.layout == JointLogFileDescription::Layout::kOneValuePerLine) {
    part.stride = file.stride;
    part.data_after = file.skip;
    part.columns = internal::TargetsOf(ExpandColumnNames(file.columns), model.n_dof(), messages,
                                       format.transmission.has_value());
    return part;
  }
  std::int64_t line_number = 0;
  const std::vector<std::string> first_fields = internal::FirstLineFields(&part.lines, part.named, file.skip, &line_number);
  part.header = !internal::AllNumbers(first_fields);
  ColumnMessages file_messages = messages;
  if (!part.named) file_messages.header_line = line_number;
  part.columns = internal::TargetsOf(
      internal::FileColumnNames(first_fields, part.header, model, columns_format, file_messages, line_number, notes),
      model.n_dof(), file_messages, format.transmission.has_value());
  part.data_after = part.named && !part.header ? file.skip : line_number;
  return part;
}

}  // namespace

std::unique_ptr<JointLogSource> OpenDescribedJointLog(const JointLogDescription& description, const RobotModel& model,
                                                      const JointLogFormat& format, TorqueColumns torques) {
  const std::string& source = description.source;
  const int n_dof = model.n_dof();
  std::vector<std::string> notes;
  const JointLogFormat merged = MergedFormat(description, format, &notes);
  std::string why;
  if (description.transmission && description.transmission->n_dof() != n_dof) {
    throw std::invalid_argument(source + ": .transmission: " + std::to_string(description.transmission->n_dof()) +
                                " actuators, the robot has " + std::to_string(n_dof) + " joints (one actuator each)");
  }
  if (description.transmission && !description.transmission->IsValid(n_dof, &why)) {
    throw std::invalid_argument(source + ": .transmission." + why);
  }
  if (!merged.IsValid(&why) || !merged.IsValidFor(n_dof, &why)) throw std::invalid_argument(source + ": " + why);

  // The files, each with its columns.
  TableLogSource::Options options;
  options.model = &model;
  options.format = merged;
  options.torques = torques;
  options.source = source;
  options.rate_hz = description.rate_hz;
  options.time_window = description.time_window;
  options.notes = std::move(notes);
  std::vector<LogPart> parts;
  for (size_t i = 0; i < description.files.size(); ++i) {
    parts.push_back(OpenPart(description, i, model, merged, &options.notes));
  }

  // The columns of all files together: each named once, then as one log's.
  internal::FileColumns all;
  std::map<std::string, size_t> part_of;
  for (size_t p = 0; p < parts.size(); ++p) {
    for (const auto& [name, column] : parts[p].columns.column_of) {
      if (const auto [at, added] = part_of.emplace(name, p); !added) {
        // Written as named in each file: qm1 and q1 are one quantity on two sides.
        const LogPart& first = parts[at->second];
        const std::string& first_name = first.columns.names[static_cast<size_t>(first.columns.column_of.at(name))];
        const std::string& this_name = parts[p].columns.names[column];
        if (first_name != this_name) {
          const bool first_actuator = first_name != name;  // qm1 is kept under q1
          const std::string kind = name.substr(0, name.find_first_of("0123456789")) + "*";
          const auto side = [&](bool actuator, const std::string& n, const LogPart& part) {
            return (actuator ? "on the actuator side ('" : "on the joint side ('") + n + "' in " + part.label + ")";
          };
          throw std::invalid_argument(source + ": columns " + kind + " " + side(first_actuator, first_name, first) +
                                      " and " + side(!first_actuator, this_name, parts[p]) +
                                      ": give each kind on one side");
        }
        throw std::invalid_argument(source + ": column '" + name + "' is in both " + first.label + " and " +
                                    parts[p].label + ": name each column in one file");
      }
      all.column_of.emplace(name, static_cast<int>(column));
    }
    all.joint_kinds |= parts[p].columns.joint_kinds;
    all.actuator_kinds |= parts[p].columns.actuator_kinds;
  }
  if (description.rate_hz && all.has("t")) {
    throw std::invalid_argument(source + ": .rate given and " + parts[part_of["t"]].label +
                                " has a time column 't': give one of them");
  }
  if (!description.rate_hz && !all.has("t")) {
    throw std::invalid_argument(source + ": no time: give .rate (the sampling rate [Hz], t = k/rate) or a column 't'");
  }
  const ColumnMessages messages{source, true, 0, source + ": .files"};
  options.use = internal::ChooseColumns(all, n_dof, merged, torques, messages, &options.warnings, false);
  if (description.files.size() > 1) {
    options.notes.push_back(source + ": " + std::to_string(description.files.size()) +
                            " files joined sample by sample" +
                            (description.rate_hz ? ", t = k/" + Shortest(*description.rate_hz) + " Hz" : ""));
  } else if (description.rate_hz) {
    options.notes.push_back(source + ": t = k/" + Shortest(*description.rate_hz) + " Hz");
  }
  return std::make_unique<TableLogSource>(std::move(parts), std::move(options));
}

}  // namespace idbench
