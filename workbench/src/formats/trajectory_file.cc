#include "idbench/workbench/formats/trajectory_file.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "idbench/excitation/constant_acceleration.h"
#include "idbench/excitation/fourier_series.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/resource_limits.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "number_format.h"
#include "idbench/engine/printable_text.h"

namespace idbench {
namespace {

using nlohmann::json;

bool EndsWith(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

nlohmann::ordered_json MatrixRows(const Eigen::MatrixXd& m) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int i = 0; i < m.rows(); ++i) rows.push_back(ToStdVector(m.row(i).transpose()));
  return rows;
}

// Reads keys of one JSON object with messages "source: key 'k': what".
class KeyReader {
 public:
  KeyReader(const json& object, std::string source) : object_(object), source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw std::invalid_argument(source_ + ": key '" + PrintableText(key) + "': " + what);
  }
  const json& Get(const std::string& key) const {
    if (!object_.contains(key)) Fail(key, "missing");
    return object_.at(key);
  }
  // A finite number; `positive` requires > 0.
  double Number(const std::string& key, bool positive) const {
    const json& v = Get(key);
    if (!v.is_number()) Fail(key, "expected a number, got " + PrintableText(v.dump()));
    const double x = v.get<double>();
    if (positive && !(x > 0.0)) Fail(key, "must be > 0, got " + PrintableText(v.dump()));
    return x;
  }
  bool Bool(const std::string& key, bool fallback) const {
    if (!object_.contains(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_boolean()) Fail(key, "expected true or false, got " + PrintableText(v.dump()));
    return v.get<bool>();
  }
  // An array of `size` numbers (one per joint).
  Eigen::VectorXd Vector(const std::string& key, int size) const {
    const json& v = Get(key);
    if (!v.is_array() || static_cast<int>(v.size()) != size) {
      Fail(key, "expected an array of " + std::to_string(size) + " numbers (one per joint of the robot), got " +
                    (v.is_array() ? std::to_string(v.size()) + " entries" : PrintableText(v.dump())));
    }
    Eigen::VectorXd x(size);
    for (int i = 0; i < size; ++i) {
      if (!v[static_cast<size_t>(i)].is_number()) Fail(key, "entry " + std::to_string(i + 1) + ": expected a number, got " + PrintableText(v[static_cast<size_t>(i)].dump()));
      x[i] = v[static_cast<size_t>(i)].get<double>();
    }
    return x;
  }
  // rows arrays of `cols` numbers each; cols < 0 takes the first row's length (>= 1).
  Eigen::MatrixXd Matrix(const std::string& key, int rows, int cols) const {
    const json& v = Get(key);
    if (!v.is_array() || static_cast<int>(v.size()) != rows) {
      Fail(key, "expected " + std::to_string(rows) + " rows (one per joint of the robot), got " +
                    (v.is_array() ? std::to_string(v.size()) : PrintableText(v.dump())));
    }
    if (cols < 0) cols = v[0].is_array() ? static_cast<int>(v[0].size()) : 0;
    if (cols < 1) Fail(key, "row 1: expected an array of at least one coefficient, got " + PrintableText(v[0].dump()));
    Eigen::MatrixXd m(rows, cols);
    for (int i = 0; i < rows; ++i) {
      const json& row = v[static_cast<size_t>(i)];
      const std::string where = "row " + std::to_string(i + 1) + ": ";
      if (!row.is_array() || static_cast<int>(row.size()) != cols) {
        Fail(key, where + "expected " + std::to_string(cols) + " numbers (one per harmonic), got " +
                      (row.is_array() ? std::to_string(row.size()) : PrintableText(row.dump())));
      }
      for (int c = 0; c < cols; ++c) {
        const json& x = row[static_cast<size_t>(c)];
        if (!x.is_number()) Fail(key, where + "entry " + std::to_string(c + 1) + ": expected a number, got " + PrintableText(x.dump()));
        m(i, c) = x.get<double>();
      }
    }
    return m;
  }
  // Rejects keys outside `known` (typos would otherwise be silently ignored).
  void OnlyKeys(const std::set<std::string>& known) const {
    for (const auto& [key, value] : object_.items()) {
      if (known.count(key)) continue;
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      Fail(key, "unknown for this family; expected " + list);
    }
  }

 private:
  const json& object_;
  std::string source_;
};

// The text with a header's q.<joint name>, qd.<..>, qdd.<..>, tau.<..>
// columns renamed to the joint's number (q3); other lines unchanged.
std::string NumberNamedColumns(const std::string& text, const RobotModel& model, const std::string& source) {
  size_t begin = 0;
  int line = 1;
  while (begin < text.size() && text.find_first_not_of(" \t\r\n", begin) != std::string::npos) {
    const size_t end = std::min(text.find('\n', begin), text.size());
    if (text.find_first_not_of(" \t\r", begin) < end) break;  // the first non-blank line
    begin = end + 1, ++line;
  }
  if (begin >= text.size()) return text;
  const size_t end = std::min(text.find('\n', begin), text.size());
  std::string header;
  int column = 0;
  for (size_t field = begin; field <= end; ++column) {
    const size_t comma = std::min(text.find(',', field), end);
    std::string name = text.substr(field, comma - field);
    const size_t dot = name.find('.');
    const std::string prefix = name.substr(0, dot);
    if (dot != std::string::npos && (prefix == "q" || prefix == "qd" || prefix == "qdd" || prefix == "tau")) {
      std::string joint = name.substr(dot + 1);
      if (!joint.empty() && joint.back() == '\r') joint.pop_back();
      int j = 0;
      while (j < model.n_dof() && model.links()[static_cast<size_t>(j)].joint_name != joint) ++j;
      if (j == model.n_dof()) {
        throw std::invalid_argument(source + ":" + std::to_string(line) + ": column " + std::to_string(column + 1) +
                                    " ('" + name + "'): no joint '" + joint + "' in " + model.name());
      }
      name = prefix + std::to_string(j + 1);
    }
    header += (column ? "," : "") + name;
    field = comma + 1;
  }
  return text.substr(0, begin) + header + text.substr(end);
}

}  // namespace

std::string FormatTrajectoryJson(const Trajectory& trajectory) {
  nlohmann::ordered_json j;  // keys in the documented order, family first
  if (const auto* f = dynamic_cast<const FourierSeriesTrajectory*>(&trajectory)) {
    j = {{"family", "fourier"},          {"f0", f->f0()},
         {"duration", f->duration()},    {"rest_to_rest", f->rest_to_rest()},
         {"q0", ToStdVector(f->q0())},   {"a", MatrixRows(f->a())},
         {"b", MatrixRows(f->b())}};
  } else if (const auto* c = dynamic_cast<const ConstantAccelerationTrajectory*>(&trajectory)) {
    j = {{"family", "constant-acceleration"}, {"duration", c->duration()},     {"q0", ToStdVector(c->q0())},
         {"qd0", ToStdVector(c->qd0())},       {"qdd", ToStdVector(c->qdd())}};
  } else {
    throw std::invalid_argument(
        "trajectory JSON: expected a Fourier series or constant-acceleration trajectory; this family has no "
        "coefficients to save (write it as CSV)");
  }
  return j.dump(2) + "\n";
}

std::unique_ptr<Trajectory> ParseTrajectoryJson(const std::string& text, int n_dof, const std::string& source) {
  const json j = ParseJsonInput(text, source);
  if (!j.is_object()) throw std::invalid_argument(source + ": expected a JSON object, got " + std::string(j.type_name()));
  const KeyReader keys(j, source);
  const json& family = keys.Get("family");
  if (family == "fourier") {
    keys.OnlyKeys({"family", "f0", "duration", "rest_to_rest", "q0", "a", "b"});
    const double f0 = keys.Number("f0", true), duration = keys.Number("duration", true);
    const bool rest_to_rest = keys.Bool("rest_to_rest", false);
    Eigen::VectorXd q0 = keys.Vector("q0", n_dof);
    Eigen::MatrixXd a = keys.Matrix("a", n_dof, -1);
    if (a.cols() > FourierSeriesTrajectory::kMaxHarmonics) {
      keys.Fail("a", std::to_string(a.cols()) + " harmonics, at most " +
                         std::to_string(FourierSeriesTrajectory::kMaxHarmonics) + " (as idbench design)");
    }
    Eigen::MatrixXd b = keys.Matrix("b", n_dof, static_cast<int>(a.cols()));
    return std::make_unique<FourierSeriesTrajectory>(std::move(q0), std::move(a), std::move(b), f0, duration,
                                                     rest_to_rest);
  }
  if (family == "constant-acceleration") {
    keys.OnlyKeys({"family", "duration", "q0", "qd0", "qdd"});
    const double duration = keys.Number("duration", true);
    return std::make_unique<ConstantAccelerationTrajectory>(keys.Vector("q0", n_dof), keys.Vector("qd0", n_dof),
                                                            keys.Vector("qdd", n_dof), duration);
  }
  keys.Fail("family", "expected \"fourier\" or \"constant-acceleration\", got " + PrintableText(family.dump()));
}

void CheckTrajectoryCsvRate(double duration, double rate_hz, int n_dof) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument("csv_rate_hz: expected a rate > 0 Hz, got " + Shortest(rate_hz));
  }
  // Each row: t and n values of q, qd, qdd as text (at most 25 characters
  // each), and the log that holds them (8 bytes each).
  CheckFitsInMemory("csv_rate_hz " + Shortest(rate_hz), std::floor(duration * rate_hz + 1e-9) + 1,
                    "rows of trajectory.csv", (25.0 + 8.0) * (1 + 3 * n_dof), "t, q, qd, qdd as text and as numbers");
}

std::string FormatTrajectoryCsv(const Trajectory& trajectory, double rate_hz, bool derivatives,
                                const std::vector<std::string>& joint_names) {
  CheckTrajectoryCsvRate(trajectory.duration(), rate_hz, trajectory.n_dof());
  if (!joint_names.empty() && static_cast<int>(joint_names.size()) != trajectory.n_dof()) {
    throw std::invalid_argument("trajectory CSV: expected " + std::to_string(trajectory.n_dof()) + " joint names, got " +
                                std::to_string(joint_names.size()));
  }
  for (const std::string& name : joint_names) {
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("trajectory CSV: joint name '" + name + "' cannot head a CSV column");
  }
  const int n_samples = static_cast<int>(std::floor(trajectory.duration() * rate_hz + 1e-9)) + 1;
  JointLog log;  // no torques: FormatJointLogCsv then writes t, q, qd, qdd
  log.t.resize(n_samples);
  log.q.resize(n_samples, trajectory.n_dof());
  log.qd.resize(n_samples, trajectory.n_dof());
  log.qdd.resize(n_samples, trajectory.n_dof());
  JointState state(trajectory.n_dof());
  for (int k = 0; k < n_samples; ++k) {
    log.t[k] = k / rate_hz;
    trajectory.Evaluate(log.t[k], &state);
    log.q.row(k) = state.q.transpose();
    log.qd.row(k) = state.qd.transpose();
    log.qdd.row(k) = state.qdd.transpose();
  }
  if (!derivatives) log.qd.resize(0, 0), log.qdd.resize(0, 0);
  std::string csv = FormatJointLogCsv(log);
  if (joint_names.empty()) return csv;
  // The header with names: q3 -> q.<name of joint 3>.
  std::string header = "t";
  for (const char* prefix : {"q", "qd", "qdd"}) {
    if (!derivatives && prefix[1] == 'd') continue;
    for (const std::string& name : joint_names) header += "," + std::string(prefix) + "." + name;
  }
  return header + csv.substr(csv.find('\n'));
}

SampledTrajectory ParseTrajectoryCsv(const std::string& text, const RobotModel& model, const std::string& source) {
  const JointLog log = ParseJointLogCsv(NumberNamedColumns(text, model, source), model, source, TorqueColumns::kOptional);
  if (log.n_samples() < 2) {
    throw std::invalid_argument(source + ": " + std::to_string(log.n_samples()) +
                                " sample, expected at least 2 to interpolate");
  }
  if (!log.has_derivatives()) return SampledTrajectory(log.t, log.q.transpose());
  return SampledTrajectory(log.t, log.q.transpose(), log.qd.transpose(), log.qdd.transpose());
}

namespace {

// A motion from a file must be one a robot could follow and a double can
// hold: q, qd, qdd finite and |q| <= 1e6 rad (where doubles still resolve
// 1e-10 rad) at 1001 instants over its duration. (f0 = 1e-300 in a Fourier
// file gives q ≈ -1.6e297 rad.)
void CheckMotionIsUsable(const Trajectory& motion, const std::string& source) {
  constexpr double kMaxAngle = 1e6;  // [rad]
  JointState state(motion.n_dof());
  for (int k = 0; k <= 1000; ++k) {
    const double t = motion.duration() * k / 1000.0;
    motion.Evaluate(t, &state);
    for (int j = 0; j < motion.n_dof(); ++j) {
      const bool finite = std::isfinite(state.q[j]) && std::isfinite(state.qd[j]) && std::isfinite(state.qdd[j]);
      if (!finite || std::abs(state.q[j]) > kMaxAngle) {
        throw std::invalid_argument(source + ": at t = " + Shortest(t) + " s joint " + std::to_string(j + 1) +
                                    " has q = " + Shortest(state.q[j]) + " rad, qd = " + Shortest(state.qd[j]) +
                                    ", qdd = " + Shortest(state.qdd[j]) +
                                    ": expected finite values and |q| <= 1e6 rad; check f0 and the coefficients");
      }
    }
  }
}

}  // namespace

bool IsTrajectoryFile(const std::string& name_or_path) {
  return EndsWith(name_or_path, ".json") || EndsWith(name_or_path, ".csv");
}

std::unique_ptr<Trajectory> LoadTrajectoryArg(const std::string& name_or_path, const RobotModel& model,
                                              const BuiltinMotionOptions& builtin) {
  if (EndsWith(name_or_path, ".json")) {
    std::unique_ptr<Trajectory> motion = ParseTrajectoryJson(ReadInputFile(name_or_path), model.n_dof(), name_or_path);
    CheckMotionIsUsable(*motion, name_or_path);
    return motion;
  }
  if (EndsWith(name_or_path, ".csv")) {
    return std::make_unique<SampledTrajectory>(ParseTrajectoryCsv(ReadInputFile(name_or_path), model, name_or_path));
  }
  const std::vector<std::string> names = BuiltinMotionNames();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
    return MakeBuiltinMotion(name_or_path, model.n_dof(), builtin);
  }
  try {
    MakeBuiltinMotion(name_or_path, model.n_dof(), builtin);
  } catch (const std::invalid_argument& e) {  // "trajectory 'x': not a built-in motion (names)"
    throw std::invalid_argument(std::string(e.what()) + " nor a file ending in .json or .csv");
  }
  throw std::logic_error("MakeBuiltinMotion accepted '" + name_or_path + "', not in BuiltinMotionNames()");
}

}  // namespace idbench
