#include "table_log_source.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "angle_unit_check.h"
#include "csv_fields.h"
#include "idbench/engine/printable_text.h"
#include "number_format.h"

namespace idbench::internal {
namespace {

bool Blank(std::string_view line) { return line.find_first_not_of(" \t\r") == std::string_view::npos; }

std::string_view Trimmed(std::string_view field) {
  while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.remove_suffix(1);
  while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
  return field;
}

// Positions the part at its first data line.
void SeekData(LogPart* part) {
  part->lines.Rewind();
  std::string_view line;
  while (part->lines.line_number() < part->data_after && part->lines.Next(&line)) {
  }
}

}  // namespace

std::vector<std::string> FirstLineFields(LineReader* lines, bool named, std::int64_t skip, std::int64_t* line_number) {
  std::string_view line;
  bool found = false;
  while (lines->Next(&line)) {
    if (lines->line_number() > skip && !Blank(line)) {
      found = true;
      break;
    }
  }
  *line_number = lines->line_number();
  if (!found) FailAt(lines->source(), std::max<std::int64_t>(*line_number, 1), named ? "empty file" : "empty file, expected a header line");
  return SplitFields(std::string(line));
}

TableLogSource::TableLogSource(std::vector<LogPart> parts, Options options)
    : parts_(std::move(parts)), options_(std::move(options)) {
  const int n_dof = options_.model->n_dof();
  const ColumnUse& use = options_.use;
  to_rad_ = options_.format.degrees() ? std::numbers::pi / 180.0 : 1.0;
  for (size_t p = 0; p < parts_.size(); ++p) {
    values_.emplace_back(parts_[p].columns.names.size(), 0.0);
    if (parts_[p].columns.has("t")) t_part_ = p;
    if (parts_[p].columns.has("q1")) q_source_ = parts_[p].lines.source();
    actuator_kinds_ |= parts_[p].columns.actuator_kinds;
  }
  if (actuator_kinds_ != 0 && !options_.format.transmission) {
    throw std::logic_error("TableLogSource: actuator-side columns without a transmission");
  }
  if (!t_part_ && !options_.rate_hz) throw std::logic_error("TableLogSource: no t column and no rate");
  layout_.source = options_.source;
  layout_.n_dof = n_dof;
  layout_.has_qd = use.has_qd;
  layout_.has_qdd = use.has_qdd;
  layout_.has_tau = use.use_tau || use.use_i;
  layout_.torque_from_currents = use.use_i && options_.torques == TorqueColumns::kRequired;
  layout_.tau_is_current = options_.torques == TorqueColumns::kCurrents;
  if (!t_part_) layout_.rate_hz = options_.rate_hz;
  layout_.time_window = options_.time_window;
  layout_.notes = options_.notes;
  layout_.warnings = options_.warnings;
  if (actuator_kinds_ != 0) {
    layout_.transmission = options_.format.transmission;
    std::string kinds;
    const std::pair<int, const char*> kActuatorKinds[] = {{1, "qm*"}, {2, "qdm*"}, {4, "taum*"}, {5, "im*"}};
    for (const auto& [kind, name] : kActuatorKinds) {
      if (actuator_kinds_ & (1u << kind)) kinds += (kinds.empty() ? "" : ", ") + std::string(name);
    }
    layout_.notes.push_back(options_.source + ": " + kinds + " read on the actuator side, mapped to the joints through "
                            "the transmission of " + options_.format.transmission->source +
                            " (q = A⁻¹·θm + q0, q̇ = A⁻¹·θ̇m, τ = Aᵀ·τm)");
  }
  Rewind();
}

void TableLogSource::Rewind() {
  for (LogPart& part : parts_) SeekData(&part);
  n_read_ = 0;
  ended_ = false;
  const int n_dof = options_.model->n_dof();
  q_min_ = Eigen::VectorXd::Constant(n_dof, std::numeric_limits<double>::infinity());
  q_max_ = -q_min_;
}

void TableLogSource::ReadValue(size_t p, size_t c, std::string_view f, std::int64_t line) {
  const LogPart& part = parts_[p];
  const ColumnTarget& target = part.columns.targets[c];
  double& value = values_[p][c];
  const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), value);
  const std::string& source = part.lines.source();
  if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) {
    FailAt(source, line, ColumnLabel(c, part.columns.names[c]) + ": '" + PrintableText(std::string(f)) + "' is not a number");
  }
  if (!std::isfinite(value)) FailAt(source, line, ColumnLabel(c, part.columns.names[c]) + ": " + std::string(f) + " is not finite");
  if (target.kind >= 1 && target.kind <= 3) value *= to_rad_;
  if (target.kind == 1 && !target.actuator) {
    const JointLimits& limits = options_.model->link(target.joint).limits;
    if (value < limits.q_min || value > limits.q_max) {
      FailAt(source, line,
             ColumnLabel(c, part.columns.names[c]) + ": " + std::string(f) +
                 (options_.format.degrees() ? " deg (" + Shortest(value) + " rad)" : " rad") + " is outside joint " +
                 std::to_string(target.joint + 1) + "'s limits [" + std::to_string(limits.q_min) + ", " +
                 std::to_string(limits.q_max) + "] rad");
    }
  }
}

bool TableLogSource::ReadSample(size_t p, std::int64_t* line_number) {
  LogPart& part = parts_[p];
  const std::vector<ColumnTarget>& targets = part.columns.targets;
  const size_t n_names = part.columns.names.size();
  std::string_view line;
  if (part.stride == 0) {
    // A CSV line: its fields, then each used one.
    do {
      if (!part.lines.Next(&line)) return false;
    } while (Blank(line));
    *line_number = part.lines.line_number();
    SplitFieldViews(line, &fields_);
    if (part.named ? fields_.size() < n_names : fields_.size() != n_names) {
      FailAt(part.lines.source(), *line_number,
             std::to_string(fields_.size()) + " fields, expected " + (part.named ? "at least " : "") +
                 std::to_string(n_names));
    }
    for (size_t c = 0; c < n_names; ++c) {
      if (targets[c].kind >= 0) ReadValue(p, c, fields_[c], *line_number);
    }
    return true;
  }
  // One value per line, stride lines per sample.
  for (size_t c = 0; c < static_cast<size_t>(part.stride); ++c) {
    do {
      if (!part.lines.Next(&line)) {
        if (c == 0) return false;
        FailAt(part.lines.source(), part.lines.line_number(),
               "the file ends within a sample: " + std::to_string(c) + " of its " + std::to_string(part.stride) +
                   " lines (stride " + std::to_string(part.stride) + ")");
      }
    } while (Blank(line));
    if (c == 0) *line_number = part.lines.line_number();
    const std::string_view field = Trimmed(line);
    if (field.find(',') != std::string_view::npos) {
      FailAt(part.lines.source(), part.lines.line_number(),
             "expected one value per line (layout one-value-per-line), got '" + PrintableText(std::string(field)) + "'");
    }
    if (targets[c].kind >= 0) ReadValue(p, c, field, part.lines.line_number());
  }
  return true;
}

void TableLogSource::FailLengths(const std::vector<bool>& got) {
  // Each part's number of samples: those read, and the rest of the longer ones counted.
  std::vector<std::int64_t> counts(parts_.size(), n_read_);
  for (size_t p = 0; p < parts_.size(); ++p) {
    if (!got[p]) continue;
    LogPart& part = parts_[p];
    std::int64_t lines = 0;
    std::string_view line;
    while (part.lines.Next(&line)) lines += !Blank(line);
    counts[p] += 1 + (part.stride == 0 ? lines : (lines + part.stride - 1) / part.stride);
  }
  size_t a = 0, b = 0;
  for (size_t p = 0; p < parts_.size(); ++p) {
    if (!got[p]) a = p;
    if (got[p]) b = p;
  }
  if (a > b) std::swap(a, b);
  throw std::invalid_argument(options_.source + ": " + parts_[a].label + " has " + std::to_string(counts[a]) +
                              " samples but " + parts_[b].label + " has " + std::to_string(counts[b]) +
                              ": the files are joined sample by sample and must have as many each");
}

void TableLogSource::ToJointSide(Eigen::Index n, JointLogChunk* chunk) {
  if (n == 0) return;
  const Transmission& transmission = *options_.format.transmission;
  JointLog& out = chunk->samples;
  const bool tau_actuator = (options_.use.use_tau && (actuator_kinds_ & (1u << 4))) ||
                            (options_.use.use_i && (actuator_kinds_ & (1u << 5)));
  if (actuator_kinds_ & (1u << 1)) out.q.topRows(n) = transmission.JointPositions(out.q.topRows(n));
  if (actuator_kinds_ & (1u << 2)) out.qd.topRows(n) = transmission.JointRates(out.qd.topRows(n));
  if (tau_actuator && out.tau.size() > 0) out.tau.topRows(n) = transmission.JointTorques(out.tau.topRows(n));
  if (!(actuator_kinds_ & (1u << 1))) return;
  // The joint positions the motors give, inside the joint limits.
  for (Eigen::Index r = 0; r < n; ++r) {
    for (int j = 0; j < out.q.cols(); ++j) {
      const JointLimits& limits = options_.model->link(j).limits;
      const double q = out.q(r, j);
      if (q < limits.q_min || q > limits.q_max) {
        FailAt(q_source_.empty() ? options_.source : q_source_, chunk->records[static_cast<size_t>(r)],
               "joint " + std::to_string(j + 1) + " at " + Shortest(q) + " rad from the motor positions (through "
               "the transmission) is outside its limits [" + std::to_string(limits.q_min) + ", " +
               std::to_string(limits.q_max) + "] rad: check the reductions and joint_offset");
      }
    }
  }
}

bool TableLogSource::Next(Eigen::Index max_samples, JointLogChunk* chunk) {
  if (max_samples < 1) throw std::invalid_argument("JointLogSource::Next: max_samples must be at least 1");
  const int n_dof = options_.model->n_dof();
  const ColumnUse& use = options_.use;
  JointLog& out = chunk->samples;
  out.t.resize(max_samples);
  out.q.resize(max_samples, n_dof);
  out.qd.resize(use.has_qd ? max_samples : 0, use.has_qd ? n_dof : 0);
  out.qdd.resize(use.has_qdd ? max_samples : 0, use.has_qdd ? n_dof : 0);
  out.tau.resize(layout_.has_tau ? max_samples : 0, layout_.has_tau ? n_dof : 0);
  chunk->records.clear();
  Eigen::MatrixXd* matrices[] = {nullptr, &out.q, &out.qd, &out.qdd, use.use_tau ? &out.tau : nullptr,
                                 use.use_i ? &out.tau : nullptr};
  const bool scale = layout_.torque_from_currents;
  const std::vector<double>& gains = options_.format.drive_gains;
  std::vector<bool> got(parts_.size());
  std::vector<std::int64_t> lines(parts_.size());
  Eigen::Index s = 0;
  while (s < max_samples && !ended_) {
    // The sample from every part; all end together or none.
    size_t n_got = 0;
    for (size_t p = 0; p < parts_.size(); ++p) n_got += (got[p] = ReadSample(p, &lines[p]));
    if (n_got == 0) {
      ended_ = true;
      break;
    }
    if (n_got != parts_.size()) FailLengths(got);

    // Time from the t column (strictly increasing) or the rate.
    double t = 0.0;
    if (t_part_) {
      const LogPart& part = parts_[*t_part_];
      const size_t t_column = static_cast<size_t>(part.columns.column_of.at("t"));
      t = values_[*t_part_][t_column];
      if (n_read_ > 0 && !(t > last_t_)) {
        FailAt(part.lines.source(), lines[*t_part_],
               "column " + std::to_string(t_column + 1) + " ('t'): time " + std::to_string(t) + " does not increase");
      }
    } else {
      t = static_cast<double>(n_read_) / *options_.rate_hz;
    }
    last_t_ = t;
    out.t[s] = t;

    // Each column into its matrix; currents × gains into tau (kRequired).
    for (size_t p = 0; p < parts_.size(); ++p) {
      const std::vector<ColumnTarget>& targets = parts_[p].columns.targets;
      const std::vector<double>& v = values_[p];
      for (size_t c = 0; c < targets.size(); ++c) {
        const ColumnTarget& target = targets[c];
        if (target.kind <= 0 || !matrices[target.kind]) continue;
        (*matrices[target.kind])(s, target.joint) =
            target.kind == 5 && scale ? gains[static_cast<size_t>(target.joint)] * v[c] : v[c];
      }
    }
    chunk->records.push_back(lines[0]);
    ++n_read_;
    ++s;
  }
  if (actuator_kinds_ != 0) ToJointSide(s, chunk);
  for (Eigen::Index r = 0; r < s; ++r) {
    for (int j = 0; j < n_dof; ++j) {
      q_min_[j] = std::min(q_min_[j], out.q(r, j));
      q_max_[j] = std::max(q_max_[j], out.q(r, j));
    }
  }
  if (ended_ && n_read_ == 0) {
    const LogPart& part = parts_[0];
    FailAt(part.lines.source(), part.lines.line_number(),
           part.stride > 0 || (part.named && !part.header) ? "no data lines" : "no data lines after the header");
  }
  // After the last sample: the degree check over the whole log's range.
  if (ended_ && !warned_) {
    warned_ = true;
    WarnIfRadiansReadAsDegrees(options_.format, options_.source, q_min_, q_max_, n_read_, &layout_.warnings);
  }
  auto trim = [&](Eigen::MatrixXd& m) {
    if (m.size() > 0) m.conservativeResize(s, n_dof);
  };
  out.t.conservativeResize(s);
  trim(out.q);
  trim(out.qd);
  trim(out.qdd);
  trim(out.tau);
  if (s == 0) out.q.resize(0, n_dof);
  return s > 0;
}

}  // namespace idbench::internal
