#include "idbench/ident/streamed_joint_equations.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

StreamedJointEquations::StreamedJointEquations(const RobotModel& model, const FrictionModel& friction,
                                               const BaseParameters& base, const StreamedEquationsSettings& settings)
    : model_(&model), friction_(friction), base_(&base), settings_(settings), n_dof_(model.n_dof()) {
  const Eigen::Index n = settings.n_samples;
  if (n < 1) throw std::invalid_argument("streamed equations: expected n_samples >= 1, got " + std::to_string(n));
  if (settings_.n_threads <= 0) settings_.n_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Per joint, the factor's columns as standard columns, and where the
  // joint's [W_j τ_j] sits in a regressor row (t last).
  factors_ = StackedFactors(base.n_base(), JointFactorColumns(model, friction, base));
  for (int j = 0; j < n_dof_; ++j) {
    const JointRowFactor& f = factors_.joints[static_cast<size_t>(j)];
    std::vector<int> standard;
    for (int k : f.columns) standard.push_back(base.independent[static_cast<size_t>(k)]);
    standard_.push_back(standard);
    offset_.push_back(width_);
    width_ += static_cast<Eigen::Index>(standard.size()) + 1;
  }
  fold_.resize(static_cast<size_t>(n_dof_));

  // The kept equations: all, or those the parallel filter keeps.
  Eigen::Index n_kept = n;
  if (settings_.filter) {
    const ParallelFilter& pf = *settings_.filter;
    std::string why;
    if (!pf.filter.IsValid(&why)) throw std::invalid_argument("parallel filter options: " + why);
    sos_ = DesignButterworthLowPass(pf.filter.order, pf.filter.cutoff_hz, pf.sample_rate_hz);
    if (n < FiltFiltMinSamples(sos_)) {
      throw std::invalid_argument("joint log: expected at least " + std::to_string(FiltFiltMinSamples(sos_)) +
                                  " samples for the filter, got " + std::to_string(n));
    }
    trim_ = ParallelFilterTrimSamples(pf.filter, pf.sample_rate_hz);
    if (n - 2 * trim_ < 1) {
      throw std::invalid_argument("joint log: " + std::to_string(n) + " samples are too few to drop " +
                                  std::to_string(trim_) + " filter-transient samples at both ends");
    }
    n_kept = (n - 2 * trim_ + pf.filter.decimation - 1) / pf.filter.decimation;
    // Margins: the filter's settling, plus the two neighbours the
    // differences of the first stage reach.
    const Eigen::Index margin = FiltFiltSettlingSamples(sos_) + 2;
    const Eigen::Index raw_cols = 1 + n_dof_ * (2 + (settings_.has_qd ? 1 : 0) + (settings_.has_qdd ? 1 : 0));
    raw_.emplace(n, raw_cols, margin, settings_.block);
    rows_.emplace(n, width_ + 1, margin, settings_.block);
  }
  if (settings_.prepared_stride > 0) {
    const Eigen::Index m = (n + settings_.prepared_stride - 1) / settings_.prepared_stride;
    prepared_.t.resize(m);
    for (Eigen::MatrixXd* x : {&prepared_.q, &prepared_.qd, &prepared_.qdd, &prepared_.tau}) x->resize(m, n_dof_);
  }
  if (settings_.series_beta.size() > 0) {
    if (settings_.series_beta.size() != base.n_base() || settings_.series_stride < 1) {
      throw std::invalid_argument("streamed equations: expected series_beta of " + std::to_string(base.n_base()) +
                                  " entries and series_stride >= 1");
    }
    const Eigen::Index m = (n_kept + settings_.series_stride - 1) / settings_.series_stride;
    series_.t.resize(m);
    series_.measured.resize(m, n_dof_);
    series_.predicted.resize(m, n_dof_);
  }
}

void StreamedJointEquations::Push(const JointLog& samples) {
  const Eigen::Index m = samples.t.size();
  auto bad = [&](const Eigen::MatrixXd& x, bool recorded) {
    return recorded ? x.rows() != m || x.cols() != n_dof_ : false;
  };
  if (bad(samples.q, true) || bad(samples.tau, true) || bad(samples.qd, settings_.has_qd || !settings_.filter) ||
      bad(samples.qdd, settings_.has_qdd || !settings_.filter) || n_pushed_ + m > settings_.n_samples) {
    throw std::invalid_argument("streamed equations: expected at most " +
                                std::to_string(settings_.n_samples - n_pushed_) + " samples of " +
                                std::to_string(n_dof_) + " joints with the recorded columns, got " +
                                std::to_string(m));
  }
  if (m == 0) return;
  if (!settings_.filter) {
    // Used as recorded: the equations of every sample.
    Eigen::MatrixXd prepared(m, 1 + 4 * n_dof_);
    prepared << samples.t, samples.q, samples.qd, samples.qdd, samples.tau;
    Equations(prepared, n_pushed_);
    n_pushed_ += m;
    return;
  }
  // Raw rows [t q (qd) (qdd) τ] into the first stage.
  input_.resize(m, 1 + n_dof_ * (2 + (settings_.has_qd ? 1 : 0) + (settings_.has_qdd ? 1 : 0)));
  Eigen::Index c = 0;
  input_.col(c++) = samples.t;
  for (const Eigen::MatrixXd* x : {&samples.q, &samples.qd, &samples.qdd, &samples.tau}) {
    if (x->size() == 0) continue;
    input_.middleCols(c, n_dof_) = *x;
    c += n_dof_;
  }
  n_pushed_ += m;
  raw_->Push(input_, [this](Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                            Eigen::Index o1) { PrepareWindow(window, w0, o0, o1); });
}

// Stage 1 (ProcessJointLog without decimation or trimming): the recorded
// signals filtered, differentiated where not recorded.
void StreamedJointEquations::PrepareWindow(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0,
                                           Eigen::Index o0, Eigen::Index o1) {
  const Eigen::Index n = settings_.n_samples, rows = window.rows();
  const bool at_start = w0 == 0, at_end = w0 + rows == n;
  const double dt = 1.0 / settings_.filter->sample_rate_hz;
  auto filtered = [&](Eigen::Index col) {
    Eigen::MatrixXd x = window.middleCols(col, n_dof_);
    FiltFiltWindow(sos_, n, at_start, at_end, x);
    return x;
  };
  Eigen::Index c = 1;
  const Eigen::MatrixXd q_f = filtered(c);
  c += n_dof_;
  Eigen::MatrixXd qd, qdd;
  if (settings_.has_qd) {
    qd = filtered(c);
    c += n_dof_;
  }
  if (settings_.has_qdd) {
    qdd = filtered(c);
    c += n_dof_;
  }
  if (settings_.has_qd) {
    if (!settings_.has_qdd) qdd = FirstDerivative(qd, dt);
  } else {
    qd = FirstDerivative(q_f, dt);
    if (!settings_.has_qdd) qdd = SecondDerivative(q_f, dt);
  }
  const Eigen::Index m = o1 - o0, first = o0 - w0;
  Eigen::MatrixXd prepared(m, 1 + 4 * n_dof_);
  prepared << window.col(0).segment(first, m), q_f.middleRows(first, m), qd.middleRows(first, m),
      qdd.middleRows(first, m), window.middleCols(c, n_dof_).middleRows(first, m);
  Equations(prepared, o0);
}

// The regressor rows of prepared samples s0, s0 + 1, … ([t q qd qdd τ] rows),
// then the parallel filter's stage, or the fold.
void StreamedJointEquations::Equations(const Eigen::MatrixXd& prepared, Eigen::Index s0) {
  const Eigen::Index m = prepared.rows();
  const int n = n_dof_;
  // Every prepared_stride-th prepared sample, for plots and playback.
  if (settings_.prepared_stride > 0) {
    const Eigen::Index k = settings_.prepared_stride;
    for (Eigen::Index s = (s0 + k - 1) / k * k; s < s0 + m; s += k) {
      const Eigen::Index r = s - s0, out = s / k;
      prepared_.t[out] = prepared(r, 0);
      prepared_.q.row(out) = prepared.block(r, 1, 1, n);
      prepared_.qd.row(out) = prepared.block(r, 1 + n, 1, n);
      prepared_.qdd.row(out) = prepared.block(r, 1 + 2 * n, 1, n);
      prepared_.tau.row(out) = prepared.block(r, 1 + 3 * n, 1, n);
    }
  }
  // Regressor rows [W_0 τ_0 | W_1 τ_1 | … | t], the samples split over threads.
  regressor_.resize(m, width_ + 1);
  auto compute = [&](Eigen::Index r_begin, Eigen::Index r_end) {
    RobotData data(*model_);
    Eigen::MatrixXd Y;
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (Eigen::Index r = r_begin; r < r_end; ++r) {
      q = prepared.block(r, 1, 1, n).transpose();
      qd = prepared.block(r, 1 + n, 1, n).transpose();
      qdd = prepared.block(r, 1 + 2 * n, 1, n).transpose();
      ComputeJointTorqueRegressor(*model_, friction_, q, qd, qdd, &data, &Y);
      for (int j = 0; j < n; ++j) {
        const std::vector<int>& cols = standard_[static_cast<size_t>(j)];
        const Eigen::Index o = offset_[static_cast<size_t>(j)], c = static_cast<Eigen::Index>(cols.size());
        for (Eigen::Index k = 0; k < c; ++k) regressor_(r, o + k) = Y(j, cols[static_cast<size_t>(k)]);
        regressor_(r, o + c) = prepared(r, 1 + 3 * n + j);
      }
      regressor_(r, width_) = prepared(r, 0);
    }
  };
  const Eigen::Index n_threads = std::min<Eigen::Index>(settings_.n_threads, std::max<Eigen::Index>(1, m / 64));
  {
    std::vector<std::jthread> threads;
    for (Eigen::Index p = 1; p < n_threads; ++p) threads.emplace_back(compute, p * m / n_threads, (p + 1) * m / n_threads);
    compute(0, m / n_threads);
  }
  if (!settings_.filter) {
    FoldRows(regressor_, s0);
    return;
  }
  rows_->Push(regressor_, [this](Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                                 Eigen::Index o1) { FoldWindow(window, w0, o0, o1); });
}

// Stage 2 (ParallelFilterStackedRows): [W τ] filtered per joint, column by
// column, the ends trimmed, every decimation-th sample kept.
void StreamedJointEquations::FoldWindow(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                                        Eigen::Index o1) {
  const Eigen::Index n = settings_.n_samples, rows = window.rows();
  const int k = settings_.filter->filter.decimation;
  // The kept samples of [o0, o1): trim_ + i·k below n − trim_.
  const Eigen::Index first = std::max(o0, trim_ + (std::max<Eigen::Index>(o0 - trim_, 0) + k - 1) / k * k);
  const Eigen::Index end = std::min(o1, n - trim_);
  if (first >= end) return;
  filtered_ = window;
  FiltFiltWindow(sos_, n, w0 == 0, w0 + rows == n, filtered_.leftCols(width_));
  const Eigen::Index m = (end - first + k - 1) / k;
  Eigen::MatrixXd kept(m, width_ + 1);
  for (Eigen::Index i = 0; i < m; ++i) kept.row(i) = filtered_.row(first + i * k - w0);
  FoldRows(kept, first);
}

// Folds equation rows [W_0 τ_0 | … | t] into the factors; records the series.
void StreamedJointEquations::FoldRows(const Eigen::Ref<const Eigen::MatrixXd>& rows, Eigen::Index) {
  const Eigen::Index m = rows.rows();
  if (settings_.series_beta.size() > 0) {
    const Eigen::Index stride = settings_.series_stride;
    for (Eigen::Index i = (n_series_kept_ + stride - 1) / stride * stride - n_series_kept_; i < m; i += stride) {
      const Eigen::Index out = (n_series_kept_ + i) / stride;
      series_.t[out] = rows(i, width_);
      for (int j = 0; j < n_dof_; ++j) {
        const JointRowFactor& f = factors_.joints[static_cast<size_t>(j)];
        const Eigen::Index o = offset_[static_cast<size_t>(j)], c = static_cast<Eigen::Index>(f.columns.size());
        double predicted = 0.0;
        for (Eigen::Index col = 0; col < c; ++col) {
          predicted += rows(i, o + col) * settings_.series_beta[f.columns[static_cast<size_t>(col)]];
        }
        series_.measured(out, j) = rows(i, o + c);
        series_.predicted(out, j) = predicted;
      }
    }
    n_series_kept_ += m;
  }
  for (int j = 0; j < n_dof_; ++j) {
    const Eigen::Index o = offset_[static_cast<size_t>(j)];
    const Eigen::Index c = static_cast<Eigen::Index>(standard_[static_cast<size_t>(j)].size());
    Eigen::MatrixXd& f = fold_[static_cast<size_t>(j)];
    f = rows.middleCols(o, c + 1);
    FoldJointRows(f, &factors_.joints[static_cast<size_t>(j)]);
  }
}

}  // namespace idbench
