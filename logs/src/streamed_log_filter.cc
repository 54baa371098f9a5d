#include "idbench/logs/streamed_log_filter.h"

#include <stdexcept>
#include <string>

namespace idbench {

StreamedLogFilter::StreamedLogFilter(const LogFilterOptions& options, double sample_rate_hz, bool has_qd,
                                     bool has_qdd, int n_dof, Eigen::Index n_samples, Eigen::Index block)
    : dt_(1.0 / sample_rate_hz), has_qd_(has_qd), has_qdd_(has_qdd), n_dof_(n_dof), n_samples_(n_samples) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("log filter options: " + why);
  if (n_dof < 1 || (has_qd && has_qdd)) {
    throw std::invalid_argument("log filter: expected n_dof >= 1 and not both qd and qdd recorded");
  }
  sos_ = DesignButterworthLowPass(options.order, options.cutoff_hz, sample_rate_hz);
  if (n_samples < FiltFiltMinSamples(sos_)) {
    throw std::invalid_argument("joint log: expected at least " + std::to_string(FiltFiltMinSamples(sos_)) +
                                " samples for the filter, got " + std::to_string(n_samples));
  }
  // The filter's settling, plus the two neighbours the differences reach.
  const Eigen::Index margin = FiltFiltSettlingSamples(sos_) + 2;
  windows_.emplace(n_samples, 1 + n_dof * (2 + (has_qd ? 1 : 0) + (has_qdd ? 1 : 0)), margin, block);
}

void StreamedLogFilter::Push(const JointLog& samples, const Sink& sink) {
  const Eigen::Index m = samples.t.size();
  auto fits = [&](const Eigen::MatrixXd& x, bool recorded) {
    return recorded ? x.rows() == m && x.cols() == n_dof_ : x.size() == 0;
  };
  if (!fits(samples.q, true) || !fits(samples.tau, true) || !fits(samples.qd, has_qd_) ||
      !fits(samples.qdd, has_qdd_)) {
    throw std::invalid_argument("log filter: expected " + std::to_string(m) + " rows of " + std::to_string(n_dof_) +
                                " joints in q, tau and the recorded qd/qdd");
  }
  // Rows [t q (qd) (qdd) τ].
  input_.resize(m, 1 + n_dof_ * (2 + (has_qd_ ? 1 : 0) + (has_qdd_ ? 1 : 0)));
  Eigen::Index c = 0;
  input_.col(c++) = samples.t;
  for (const Eigen::MatrixXd* x : {&samples.q, &samples.qd, &samples.qdd, &samples.tau}) {
    if (x->size() == 0) continue;
    input_.middleCols(c, n_dof_) = *x;
    c += n_dof_;
  }
  windows_->Push(input_, [&](Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                             Eigen::Index o1) { Window(window, w0, o0, o1, sink); });
}

void StreamedLogFilter::Window(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                               Eigen::Index o1, const Sink& sink) const {
  const bool at_start = w0 == 0, at_end = w0 + window.rows() == n_samples_;
  auto filtered = [&](Eigen::Index col) {
    Eigen::MatrixXd x = window.middleCols(col, n_dof_);
    FiltFiltWindow(sos_, n_samples_, at_start, at_end, x);
    return x;
  };
  // As ProcessJointLog: q filtered; a recorded qd filtered and qdd its
  // difference (or a recorded qdd filtered); else both differences of q.
  Eigen::Index c = 1;
  const Eigen::MatrixXd q_f = filtered(c);
  c += n_dof_;
  Eigen::MatrixXd qd, qdd;
  if (has_qd_) {
    qd = filtered(c);
    c += n_dof_;
    qdd = FirstDerivative(qd, dt_);
  } else {
    qd = FirstDerivative(q_f, dt_);
    if (has_qdd_) {
      qdd = filtered(c);
      c += n_dof_;
    } else {
      qdd = SecondDerivative(q_f, dt_);
    }
  }
  const Eigen::Index m = o1 - o0, first = o0 - w0;
  JointLog prepared;
  prepared.t = window.col(0).segment(first, m);
  prepared.q = q_f.middleRows(first, m);
  prepared.qd = qd.middleRows(first, m);
  prepared.qdd = qdd.middleRows(first, m);
  prepared.tau = window.middleCols(c, n_dof_).middleRows(first, m);
  sink(prepared, o0);
}

}  // namespace idbench
