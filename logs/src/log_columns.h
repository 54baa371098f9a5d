// A joint log's columns (README.md, "Joint logs"): named by a header or a
// columns list (or both, reconciled), each checked against the robot, and
// which of them fill the log. Shared by every file a log is read from (a
// CSV, the files of a log description).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "column_names.h"
#include "idbench/engine/robot_model.h"
#include "idbench/logs/joint_log_format.h"

namespace idbench::internal {

// "source:line: what".
[[noreturn]] void FailAt(const std::string& source, std::int64_t line, const std::string& what);

// Where a problem with the columns is reported: the columns list when it
// names them, else the header line.
struct ColumnMessages {
  std::string source;        // the data file
  bool named;                // a columns list names the columns
  std::int64_t header_line;  // 0 when named
  std::string list;          // the columns list as messages name it; "": "<source>: columns"

  // "<list>: what" when named, else "source:header_line: what".
  [[noreturn]] void Fail(const std::string& what) const;
  std::string ListName() const { return list.empty() ? source + ": columns" : list; }
};

// The file's columns: the name of each, where its values go, and the column
// of each name used.
struct FileColumns {
  std::vector<std::string> names;
  std::vector<ColumnTarget> targets;
  std::map<std::string, int> column_of;  // actuator-side columns under their kind's joint-side name (qm2: q2)
  unsigned joint_kinds = 0, actuator_kinds = 0;  // bit `kind`: a column of that kind on that side
  bool has(const std::string& name) const { return column_of.count(name) > 0; }
};

// Which of the optional columns the log fills.
struct ColumnUse {
  bool has_qd = false, has_qdd = false;
  bool use_tau = false;  // log.tau from the tau columns
  bool use_i = false;    // log.tau from the i columns (K·i, or the currents for kCurrents)
};

// The name of each file column from its first line: the header's (q.<joint
// name> read as that joint's number), the columns list's (format.columns),
// or both reconciled. A header-less file needs a columns list (the hint
// names `messages.list`); a header naming joints the robot does not have,
// or fewer than it has, is another robot's log. Throws "source:line: ...".
std::vector<std::string> FileColumnNames(const std::vector<std::string>& first_fields, bool header,
                                         const RobotModel& model, const JointLogFormat& format,
                                         const ColumnMessages& messages, std::int64_t line_number,
                                         std::vector<std::string>* notes);

// Every column named once, from a known set, of a joint the robot has;
// actuator-side names (qm, qdm, taum, im) are read with a transmission
// (as their kind's joint-side name in column_of), else refused as needing one.
FileColumns TargetsOf(std::vector<std::string> names, int n_dof, const ColumnMessages& messages,
                      bool with_transmission = false);

// Required columns (t unless `need_t` is false), each other kind as a
// complete set or not at all, and which torque columns fill log.tau as
// `torques` asks; warnings name messages.source.
ColumnUse ChooseColumns(const FileColumns& columns, int n_dof, const JointLogFormat& format, TorqueColumns torques,
                        const ColumnMessages& messages, std::vector<std::string>* warnings, bool need_t = true);

}  // namespace idbench::internal
