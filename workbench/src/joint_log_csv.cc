#include "joint_log_csv.h"

#include "number_format.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

// Splits one CSV line on commas (no quoting: every field is a name or a number).
std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.pop_back();
    const size_t first = field.find_first_not_of(" \t");
    fields.push_back(first == std::string::npos ? "" : field.substr(first));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

// Where a column's values go: matrix (0 t, 1 q, 2 qd, 3 qdd, 4 tau) and joint.
struct ColumnTarget {
  int kind;
  int joint;
};

}  // namespace

std::string FormatJointLogCsv(const JointLog& log) {
  const int n = log.n_dof();
  const bool derivatives = log.has_derivatives();
  const bool torques = log.tau.size() > 0;
  std::string out = "t";
  for (const char* prefix : {"q", "qd", "qdd", "tau"}) {
    if (!derivatives && prefix[1] == 'd') continue;
    if (!torques && prefix[0] == 't') continue;
    for (int j = 1; j <= n; ++j) out += "," + std::string(prefix) + std::to_string(j);
  }
  out += '\n';
  out.reserve(out.size() + static_cast<size_t>(log.n_samples()) * static_cast<size_t>(4 * n + 1) * 24);
  for (int s = 0; s < log.n_samples(); ++s) {
    AppendShortest(&out, log.t[s]);
    auto row = [&](const Eigen::MatrixXd& m) {
      for (int j = 0; j < n; ++j) {
        out.push_back(',');
        AppendShortest(&out, m(s, j));
      }
    };
    row(log.q);
    if (derivatives) {
      row(log.qd);
      row(log.qdd);
    }
    if (torques) row(log.tau);
    out.push_back('\n');
  }
  return out;
}

JointLog ParseJointLogCsv(const std::string& text, const RobotModel& model, const std::string& source,
                          TorqueColumns torques) {
  const int n_dof = model.n_dof();
  auto fail = [&](int line, const std::string& what) -> void {
    throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
  };
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  // Header: every column named once, from a known set.
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  if (line_number == 0 || line.find_first_not_of(" \t\r") == std::string::npos) fail(1, "empty file, expected a header line");
  const std::vector<std::string> names = SplitFields(line);
  std::map<std::string, int> column_of;
  std::vector<ColumnTarget> targets;
  for (size_t c = 0; c < names.size(); ++c) {
    const std::string& name = names[c];
    const std::string where = "column " + std::to_string(c + 1) + " ('" + name + "')";
    if (!column_of.emplace(name, static_cast<int>(c)).second) fail(line_number, where + ": repeated");
    ColumnTarget target{-1, 0};
    if (name == "t") {
      target = {0, 0};
    } else {
      size_t digits = name.find_first_of("0123456789");
      const std::string prefix = name.substr(0, digits);
      int joint = 0;
      const char* end = name.data() + name.size();
      const auto [ptr, ec] = digits == std::string::npos ? std::from_chars(end, end, joint)
                                                         : std::from_chars(name.data() + digits, end, joint);
      const int kind = prefix == "q" ? 1 : prefix == "qd" ? 2 : prefix == "qdd" ? 3 : prefix == "tau" ? 4 : -1;
      if (kind < 0 || digits == std::string::npos || ec != std::errc() || ptr != end || joint < 1) {
        fail(line_number, where + ": unknown column; expected t, q1..q" + std::to_string(n_dof) + ", qd*, qdd*, tau*");
      }
      if (joint > n_dof) {
        fail(line_number, where + ": joint " + std::to_string(joint) + " but the robot has " +
                              std::to_string(n_dof) + " joints");
      }
      target = {kind, joint - 1};
    }
    targets.push_back(target);
  }
  // Required columns, and qd/qdd (and optional tau) as complete sets or not at all.
  auto has = [&](const std::string& name) { return column_of.count(name) > 0; };
  if (!has("t")) fail(line_number, "missing column 't'");
  const bool has_tau = torques == TorqueColumns::kRequired || has("tau1");
  for (const char* prefix : {"q", "tau"}) {
    for (int j = 1; j <= n_dof; ++j) {
      const std::string name = prefix + std::to_string(j);
      if (prefix[0] == 't' && !has_tau) {
        if (has(name)) fail(line_number, "column '" + name + "' without tau1: give all of tau1..tau" + std::to_string(n_dof) + " or none");
        continue;
      }
      if (!has(name)) fail(line_number, "missing column '" + name + "' (robot has " + std::to_string(n_dof) + " joints)");
    }
  }
  const bool derivatives = has("qd1") || has("qdd1");
  for (const char* prefix : {"qd", "qdd"}) {
    for (int j = 1; j <= n_dof && derivatives; ++j) {
      const std::string name = prefix + std::to_string(j);
      if (!has(name)) fail(line_number, "missing column '" + name + "': give all of qd1..qdd" + std::to_string(n_dof) + " or none");
    }
    for (int j = 1; j <= n_dof && !derivatives; ++j) {
      if (has(prefix + std::to_string(j))) fail(line_number, "column '" + std::string(prefix) + std::to_string(j) + "' without qd1/qdd1");
    }
  }

  // Data lines.
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = SplitFields(line);
    if (fields.size() != names.size()) {
      fail(line_number, std::to_string(fields.size()) + " fields, expected " + std::to_string(names.size()));
    }
    std::vector<double> values(fields.size());
    for (size_t c = 0; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), values[c]);
      const std::string where = "column " + std::to_string(c + 1) + " ('" + names[c] + "')";
      if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) fail(line_number, where + ": '" + f + "' is not a number");
      if (!std::isfinite(values[c])) fail(line_number, where + ": " + f + " is not finite");
      if (targets[c].kind == 1) {
        const JointLimits& limits = model.link(targets[c].joint).limits;
        if (values[c] < limits.q_min || values[c] > limits.q_max) {
          fail(line_number, where + ": " + f + " rad is outside joint " + std::to_string(targets[c].joint + 1) +
                                "'s limits [" + std::to_string(limits.q_min) + ", " + std::to_string(limits.q_max) + "]");
        }
      }
    }
    const double t = values[static_cast<size_t>(column_of["t"])];
    if (!rows.empty() && !(t > rows.back()[static_cast<size_t>(column_of["t"])])) {
      fail(line_number, "column " + std::to_string(column_of["t"] + 1) + " ('t'): time " + std::to_string(t) +
                            " does not increase");
    }
    rows.push_back(std::move(values));
  }
  if (rows.empty()) fail(line_number, "no data lines after the header");

  // Columns into the log's matrices.
  const int n_samples = static_cast<int>(rows.size());
  JointLog log;
  log.t.resize(n_samples);
  log.q.resize(n_samples, n_dof);
  if (has_tau) log.tau.resize(n_samples, n_dof);
  if (derivatives) {
    log.qd.resize(n_samples, n_dof);
    log.qdd.resize(n_samples, n_dof);
  }
  Eigen::MatrixXd* matrices[] = {nullptr, &log.q, &log.qd, &log.qdd, &log.tau};
  for (int s = 0; s < n_samples; ++s) {
    for (size_t c = 0; c < targets.size(); ++c) {
      const double v = rows[static_cast<size_t>(s)][c];
      if (targets[c].kind == 0) {
        log.t[s] = v;
      } else {
        (*matrices[targets[c].kind])(s, targets[c].joint) = v;
      }
    }
  }
  return log;
}

JointLog ReadJointLogCsv(const std::string& path, const RobotModel& model) {
  return ParseJointLogCsv(ReadTextFile(path), model, path);
}

std::string ReadTextFile(const std::string& path) {
  std::error_code ec;
  std::ifstream file(path, std::ios::binary);
  if (!file || std::filesystem::is_directory(path, ec)) throw std::invalid_argument(path + ": cannot read the file");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace idbench
