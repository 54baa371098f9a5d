#include "idbench/logs/recorded_joint_log_source.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace idbench {
namespace {

// Rows [begin, begin + count) of m, or m itself when it is empty (not recorded).
Eigen::MatrixXd Rows(const Eigen::MatrixXd& m, Eigen::Index begin, Eigen::Index count) {
  if (m.size() == 0) return Eigen::MatrixXd();
  return m.middleRows(begin, count);
}

// Appends b's rows below a's (a empty: b), for matrices recorded in both or neither.
void AppendRows(Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::Index filled) {
  if (b.size() == 0) return;
  if (a.rows() < filled + b.rows()) a.conservativeResize(std::max(2 * a.rows(), filled + b.rows()), b.cols());
  a.middleRows(filled, b.rows()) = b;
}

}  // namespace

RecordedJointLogSource::RecordedJointLogSource(RecordedJointLog log, std::string source, bool tau_is_current)
    : log_(std::move(log)) {
  layout_.source = std::move(source);
  layout_.n_dof = log_.log.n_dof();
  layout_.has_qd = log_.log.qd.size() > 0;
  layout_.has_qdd = log_.log.qdd.size() > 0;
  layout_.has_tau = log_.log.tau.size() > 0;
  layout_.torque_from_currents = log_.torque_from_currents;
  layout_.tau_is_current = tau_is_current;
  layout_.notes = log_.notes;
  layout_.warnings = log_.warnings;
}

bool RecordedJointLogSource::Next(Eigen::Index max_samples, JointLogChunk* chunk) {
  if (max_samples < 1) throw std::invalid_argument("JointLogSource::Next: max_samples must be at least 1");
  const Eigen::Index count = std::min<Eigen::Index>(max_samples, log_.log.t.size() - next_);
  JointLog& out = chunk->samples;
  out.t = log_.log.t.segment(next_, count);
  out.q = log_.log.q.middleRows(next_, count);
  out.qd = Rows(log_.log.qd, next_, count);
  out.qdd = Rows(log_.log.qdd, next_, count);
  out.tau = Rows(log_.log.tau, next_, count);
  chunk->records.assign(log_.lines.begin() + next_, log_.lines.begin() + next_ + count);
  next_ += count;
  return count > 0;
}

RecordedJointLog ReadWholeLog(JointLogSource& source, Eigen::Index chunk_samples) {
  const JointLogLayout& layout = source.layout();
  RecordedJointLog out;
  out.torque_from_currents = layout.torque_from_currents;
  JointLog& log = out.log;
  Eigen::Index filled = 0;
  JointLogChunk chunk;
  while (source.Next(chunk_samples, &chunk)) {
    const JointLog& part = chunk.samples;
    const Eigen::Index n = part.t.size();
    if (log.t.size() < filled + n) log.t.conservativeResize(std::max(2 * log.t.size(), filled + n));
    log.t.segment(filled, n) = part.t;
    AppendRows(log.q, part.q, filled);
    AppendRows(log.qd, part.qd, filled);
    AppendRows(log.qdd, part.qdd, filled);
    AppendRows(log.tau, part.tau, filled);
    for (std::int64_t record : chunk.records) out.lines.push_back(static_cast<int>(record));
    filled += n;
  }
  log.t.conservativeResize(filled);
  auto trim = [&](Eigen::MatrixXd& m) {
    if (m.size() > 0) m.conservativeResize(filled, m.cols());
  };
  trim(log.q);
  trim(log.qd);
  trim(log.qdd);
  trim(log.tau);
  if (log.q.size() == 0) log.q.resize(filled, layout.n_dof);
  // After the last chunk: what needed the whole log (e.g. the degree check).
  out.notes = layout.notes;
  out.warnings = layout.warnings;
  return out;
}

}  // namespace idbench
