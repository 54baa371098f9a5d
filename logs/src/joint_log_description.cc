#include "idbench/logs/joint_log_description.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/printable_text.h"
#include "number_format.h"
#include "yaml_input.h"

namespace idbench {
namespace {

using json = nlohmann::json;

// A YAML document as JSON: plain scalars typed as YAML 1.2's core schema
// types them (integers, floats, true/false, null), quoted ones as strings.
json FromYaml(const YAML::Node& node, const std::string& source) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return nullptr;
    case YAML::NodeType::Sequence: {
      json out = json::array();
      for (const YAML::Node& item : node) out.push_back(FromYaml(item, source));
      return out;
    }
    case YAML::NodeType::Map: {
      json out = json::object();
      for (const auto& item : node) {
        const std::string key = item.first.Scalar();
        if (out.contains(key)) {
          throw std::invalid_argument(source + ":" + std::to_string(item.first.Mark().line + 1) + ": key '" +
                                      PrintableText(key) + "' repeated");
        }
        out[key] = FromYaml(item.second, source);
      }
      return out;
    }
    case YAML::NodeType::Scalar: {
      const std::string& text = node.Scalar();
      if (node.Tag() == "!") return text;  // quoted
      const char* end = text.data() + text.size();
      long long integer = 0;
      if (auto [ptr, ec] = std::from_chars(text.data(), end, integer); ec == std::errc() && ptr == end) return integer;
      double number = 0.0;
      if (auto [ptr, ec] = std::from_chars(text.data(), end, number); ec == std::errc() && ptr == end && !text.empty()) {
        return number;
      }
      if (text == "true") return true;
      if (text == "false") return false;
      if (text == "null" || text == "~") return nullptr;
      return text;
    }
  }
  return nullptr;
}

// Checks a JSON value at a path ("source: .files[1].stride: what").
struct Field {
  const std::string& source;
  std::string path;  // jq-style: .files[1].stride
  const json& value;

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument(source + ": " + path + ": " + what);
  }
  Field operator[](const std::string& key) const { return {source, path + "." + key, value.at(key)}; }
  Field at(size_t i) const { return {source, path + "[" + std::to_string(i) + "]", value.at(i)}; }
  std::string Shown() const {
    // NaN and ±inf (from YAML: JSON has none) as such; dump() writes null.
    if (value.is_number_float() && !std::isfinite(value.get<double>())) return Shortest(value.get<double>());
    // Invalid UTF-8 (YAML passes any byte) as U+FFFD: dump() would throw.
    const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
    return PrintableText(text, 64);
  }

  // Every key one of `known`, listed quoted as written in a description (a
  // front end respells bare field names as its options: time_window).
  void Keys(std::initializer_list<const char*> known) const {
    if (!value.is_object()) Fail("expected an object {...}, got " + Shown());
    for (const auto& [key, item] : value.items()) {
      bool ok = false;
      std::string list;
      for (const char* k : known) {
        ok = ok || key == k;
        list += (list.empty() ? "\"" : ", \"") + std::string(k) + "\"";
      }
      if (!ok) {
        throw std::invalid_argument(source + ": " + path + "." + PrintableText(key) + ": unknown key; expected " + list);
      }
    }
  }
  std::string String() const {
    if (!value.is_string()) Fail("expected a string, got " + Shown());
    return value.get<std::string>();
  }
  double Number() const {
    if (!value.is_number()) Fail("expected a number, got " + Shown());
    const double v = value.get<double>();
    if (!std::isfinite(v)) Fail("expected a finite number, got " + Shown());
    return v;
  }
  int Integer(int lo, int hi) const {
    const double v = value.is_number() ? value.get<double>() : NAN;
    if (!(v >= lo && v <= hi) || v != std::floor(v)) {
      Fail("expected a whole number " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + Shown());
    }
    return static_cast<int>(v);
  }
  std::vector<double> Numbers() const {
    if (!value.is_array()) Fail("expected a list of numbers, got " + Shown());
    std::vector<double> out;
    for (size_t i = 0; i < value.size(); ++i) out.push_back(at(i).Number());
    return out;
  }
  // "t,q1..q6" or ["t", "q1..q6"].
  std::vector<std::string> Columns() const {
    std::vector<std::string> out;
    if (value.is_string()) {
      const std::string list = value.get<std::string>();
      size_t start = 0;
      for (size_t comma = list.find(','); ; comma = list.find(',', start)) {
        std::string item = list.substr(start, comma == std::string::npos ? comma : comma - start);
        const size_t first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
        out.push_back(first == std::string::npos ? "" : item.substr(first, last - first + 1));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    } else if (value.is_array()) {
      for (size_t i = 0; i < value.size(); ++i) out.push_back(at(i).String());
    } else {
      Fail("expected column names, as \"t,q1..q6\" or [\"t\", \"q1..q6\"], got " + Shown());
    }
    if (static_cast<int>(out.size()) > JointLogFormat::kMaxColumns) {
      Fail(std::to_string(out.size()) + " items, at most " + std::to_string(JointLogFormat::kMaxColumns));
    }
    JointLogFormat format;
    format.columns = out;
    std::string why;
    // Names checked as the columns option's are; the t column may be in another file.
    if (!format.IsValid(&why) && why != "columns: no 't' column") {
      Fail(why.starts_with("columns: ") ? why.substr(9) : why);
    }
    return out;
  }
};

JointLogFileDescription ParseFile(const Field& file) {
  file.Keys({"path", "layout", "stride", "columns", "skip"});
  JointLogFileDescription out;
  if (!file.value.contains("path")) file.Fail("no \"path\": give the file's path (relative to the description)");
  out.path = file["path"].String();
  if (out.path.empty()) file["path"].Fail("empty");
  if (file.value.contains("layout")) {
    const std::string layout = file["layout"].String();
    if (layout == "one-value-per-line") {
      out.layout = JointLogFileDescription::Layout::kOneValuePerLine;
    } else if (layout != "csv") {
      file["layout"].Fail("expected \"csv\" or \"one-value-per-line\", got " + file["layout"].Shown());
    }
  }
  const bool one_per_line = out.layout == JointLogFileDescription::Layout::kOneValuePerLine;
  if (file.value.contains("stride")) {
    if (!one_per_line) file["stride"].Fail("only with \"layout\": \"one-value-per-line\"");
    out.stride = file["stride"].Integer(1, JointLogDescription::kMaxStride);
  } else if (one_per_line) {
    file.Fail("\"layout\": \"one-value-per-line\" needs \"stride\": the number of lines per sample");
  }
  if (file.value.contains("columns")) out.columns = file["columns"].Columns();
  if (file.value.contains("skip")) out.skip = file["skip"].Integer(0, JointLogDescription::kMaxSkip);
  if (one_per_line) {
    if (out.columns.empty()) file.Fail("a one-value-per-line file needs \"columns\" (the stride's values in order)");
    const size_t n = ExpandColumnNames(out.columns).size();
    if (static_cast<int>(n) != out.stride) {
      file["columns"].Fail("names " + std::to_string(n) + " columns but \"stride\" is " + std::to_string(out.stride) +
                           ": name one column per line of a sample (\"_\" skips one)");
    }
  }
  return out;
}

// {"reduction": [...]} or {"actuator_from_joint": [[...], ...]}, and an
// optional "joint_offset": checked here as far as the robot is not needed
// (square, finite, invertible, non-zero reductions; sizes against it when opened).
Transmission ParseTransmission(const Field& field) {
  field.Keys({"reduction", "actuator_from_joint", "joint_offset"});
  const bool reduction = field.value.contains("reduction"), matrix = field.value.contains("actuator_from_joint");
  if (reduction == matrix) {
    field.Fail("expected \"reduction\": [N1, ...] (gear ratios) or \"actuator_from_joint\": [[...], ...] (a square "
               "matrix A, θ̇m = A·q̇), one of them");
  }
  Transmission out;
  out.source = field.path.empty() ? field.source : field.source + ": " + field.path;
  if (reduction) {
    const Field n = field["reduction"];
    const std::vector<double> ratios = n.Numbers();
    if (ratios.empty() || static_cast<int>(ratios.size()) > JointLogFormat::kMaxJoints) {
      n.Fail("expected 1 to " + std::to_string(JointLogFormat::kMaxJoints) + " gear ratios, got " + n.Shown());
    }
    for (size_t j = 0; j < ratios.size(); ++j) {
      if (ratios[j] == 0.0) n.at(j).Fail("expected a non-zero gear ratio (θm = N·q), got 0");
      // Named here as written (not as the matrix Transmission::IsValid checks).
      if (!(std::abs(ratios[j]) <= Transmission::kMaxRatio)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", ratios[j]);  // as Transmission::IsValid shows a matrix entry
        n.at(j).Fail("expected a gear ratio of magnitude at most " + Shortest(Transmission::kMaxRatio) +
                     " (beyond any drive), got " + text);
      }
    }
    out = Transmission::FromReduction(ratios);
    out.source = field.path.empty() ? field.source : field.source + ": " + field.path;
  } else {
    const Field a = field["actuator_from_joint"];
    if (!a.value.is_array() || a.value.empty() || static_cast<int>(a.value.size()) > JointLogFormat::kMaxJoints) {
      a.Fail("expected a square matrix as a list of rows [[...], ...], got " + a.Shown());
    }
    const Eigen::Index n = static_cast<Eigen::Index>(a.value.size());
    out.actuator_from_joint.resize(n, n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const std::vector<double> row = a.at(static_cast<size_t>(k)).Numbers();
      if (static_cast<Eigen::Index>(row.size()) != n) {
        a.at(static_cast<size_t>(k)).Fail("expected " + std::to_string(n) + " values (a square matrix, one row per "
                                          "actuator), got " + std::to_string(row.size()));
      }
      for (Eigen::Index j = 0; j < n; ++j) out.actuator_from_joint(k, j) = row[static_cast<size_t>(j)];
    }
  }
  if (field.value.contains("joint_offset")) {
    const std::vector<double> offset = field["joint_offset"].Numbers();
    out.joint_offset = Eigen::Map<const Eigen::VectorXd>(offset.data(), static_cast<Eigen::Index>(offset.size()));
  }
  std::string why;
  if (!out.IsValid(out.n_dof(), &why)) throw std::invalid_argument(field.source + ": " + field.path + "." + why);
  return out;
}

}  // namespace

bool IsJointLogDescriptionPath(const std::string& path) {
  for (const char* ext : {".json", ".yaml", ".yml"}) {
    if (path.ends_with(ext)) return true;
  }
  return false;
}

namespace {

// The text as JSON (YAML converted), syntax errors naming the line.
json ParseDocument(const std::string& text, const std::string& source, bool yaml) {
  if (!yaml) return ParseJsonInput(text, source);
  try {
    return FromYaml(internal::LoadYamlWithoutAliases(text, source), source);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(source + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                                ": not valid YAML: " + e.msg);
  }
}

}  // namespace

Transmission ParseTransmissionText(const std::string& text, const std::string& source, bool yaml) {
  const json document = ParseDocument(text, source, yaml);
  return ParseTransmission(Field{source, "", document});
}

JointLogDescription ParseJointLogDescription(const std::string& text, const std::string& source, bool yaml) {
  const json document = ParseDocument(text, source, yaml);

  // Every key known, every value of its type and within its bounds.
  const Field top{source, "", document};
  if (!document.is_object()) {
    throw std::invalid_argument(source + ": expected an object with \"files\" (and \"rate\", \"time_window\", ...), got " +
                                top.Shown());
  }
  top.Keys({"rate", "files", "time_window", "angle_unit", "drive_gains", "transmission"});
  JointLogDescription out;
  out.source = source;
  if (document.contains("rate")) {
    const Field field = top["rate"];
    const double rate = field.value.is_number() ? field.value.get<double>() : NAN;
    if (!(rate >= JointLogDescription::kMinRateHz && rate <= JointLogDescription::kMaxRateHz)) {
      field.Fail("expected a sampling rate in Hz, " + Shortest(JointLogDescription::kMinRateHz) + " to " +
                 Shortest(JointLogDescription::kMaxRateHz) + ", got " + field.Shown());
    }
    out.rate_hz = rate;
  }
  if (!document.contains("files")) {
    throw std::invalid_argument(source + ": no \"files\": list the log's files, e.g. \"files\": [{\"path\": "
                                "\"log.csv\"}]");
  }
  const Field files = top["files"];
  if (!files.value.is_array() || files.value.empty() ||
      static_cast<int>(files.value.size()) > JointLogDescription::kMaxFiles) {
    files.Fail("expected a list of 1 to " + std::to_string(JointLogDescription::kMaxFiles) + " files, got " +
               (files.value.is_array() ? std::to_string(files.value.size()) + " files" : files.Shown()));
  }
  for (size_t i = 0; i < files.value.size(); ++i) out.files.push_back(ParseFile(files.at(i)));
  if (document.contains("time_window")) {
    out.time_window = top["time_window"].Numbers();
    if (out.time_window.size() != 2 || !(out.time_window[0] < out.time_window[1])) {
      top["time_window"].Fail("expected [T0, T1] [s] with T0 < T1, got " + top["time_window"].Shown());
    }
  }
  if (document.contains("angle_unit")) {
    out.angle_unit = top["angle_unit"].String();
    if (*out.angle_unit != "rad" && *out.angle_unit != "deg") {
      top["angle_unit"].Fail("expected \"rad\" or \"deg\", got " + top["angle_unit"].Shown());
    }
  }
  if (document.contains("drive_gains")) {
    out.drive_gains = top["drive_gains"].Numbers();
    JointLogFormat format;
    format.drive_gains = out.drive_gains;
    std::string why;
    if (!format.IsValid(&why)) top["drive_gains"].Fail(why.starts_with("drive_gains: ") ? why.substr(13) : why);
  }
  if (document.contains("transmission")) out.transmission = ParseTransmission(top["transmission"]);
  return out;
}

JointLogDescription ReadJointLogDescription(const std::string& path) {
  CheckInputFile(path);
  const std::string text = ReadInputFile(path);
  if (text.size() > static_cast<size_t>(JointLogDescription::kMaxBytes)) {
    throw std::invalid_argument(path + ": " + std::to_string(text.size()) + " bytes, more than a log description's " +
                                std::to_string(JointLogDescription::kMaxBytes) + "; is it the log itself?");
  }
  return ParseJointLogDescription(text, path, !path.ends_with(".json"));
}

}  // namespace idbench
