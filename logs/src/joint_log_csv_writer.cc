#include "idbench/logs/joint_log_csv_writer.h"

#include <stdexcept>
#include <string>

#include "number_format.h"

namespace idbench {

std::string FormatJointLogCsv(const JointLog& log, const Eigen::MatrixXd* q_ref) {
  const int n = log.n_dof();
  if (q_ref && (q_ref->rows() != log.n_samples() || q_ref->cols() != n)) {
    throw std::invalid_argument("FormatJointLogCsv: expected a reference of " + std::to_string(log.n_samples()) +
                                " x " + std::to_string(n) + ", got " + std::to_string(q_ref->rows()) + " x " +
                                std::to_string(q_ref->cols()));
  }
  const bool derivatives = log.has_derivatives();
  const bool torques = log.tau.size() > 0;
  std::string out = "t";
  for (const char* prefix : {"q", "qd", "qdd", "tau"}) {
    if (!derivatives && prefix[1] == 'd') continue;
    if (!torques && prefix[0] == 't') continue;
    for (int j = 1; j <= n; ++j) out += "," + std::string(prefix) + std::to_string(j);
  }
  if (q_ref) {
    for (int j = 1; j <= n; ++j) out += ",qr" + std::to_string(j);
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
    if (q_ref) row(*q_ref);
    out.push_back('\n');
  }
  return out;
}

}  // namespace idbench
