#include "idbench/ident/streamed_joint_equations.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

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
    rows_.emplace(n, width_ + 1, FiltFiltSettlingSamples(sos_), settings_.block);
  }
  if (settings_.score_fit) {
    const LinearFit& fit = *settings_.score_fit;
    if (fit.beta.size() != base.n_base() || fit.row_weights.size() != n_dof_) {
      throw std::invalid_argument("streamed equations: expected a score fit of " + std::to_string(base.n_base()) +
                                  " parameters and " + std::to_string(n_dof_) + " joint weights, got " +
                                  std::to_string(fit.beta.size()) + " and " + std::to_string(fit.row_weights.size()));
    }
    if (!settings_.scores_into) scores_.emplace(base.n_base(), n_kept, settings_.score_block_samples);
    score_.resize(base.n_base());
  }
  if (settings_.series_beta.size() > 0) {
    if (settings_.series_beta.size() != base.n_base() || settings_.series_stride < 1) {
      throw std::invalid_argument("streamed equations: expected series_beta of " + std::to_string(base.n_base()) +
                                  " entries and series_stride >= 1");
    }
    if (settings_.series_max_points > 0) {
      settings_.series_stride =
          std::max(settings_.series_stride, (n_kept + settings_.series_max_points - 1) / settings_.series_max_points);
    }
    const Eigen::Index m = (n_kept + settings_.series_stride - 1) / settings_.series_stride;
    series_.t.resize(m);
    series_.measured.resize(m, n_dof_);
    series_.predicted.resize(m, n_dof_);
  }
}

void StreamedJointEquations::Push(const JointLog& samples) {
  const Eigen::Index m = samples.t.size();
  auto fits = [&](const Eigen::MatrixXd& x) { return x.rows() == m && x.cols() == n_dof_; };
  if (!fits(samples.q) || !fits(samples.qd) || !fits(samples.qdd) || !fits(samples.tau) ||
      n_pushed_ + m > settings_.n_samples) {
    throw std::invalid_argument("streamed equations: expected at most " +
                                std::to_string(settings_.n_samples - n_pushed_) + " samples of " +
                                std::to_string(n_dof_) + " joints with q, qd, qdd and tau, got " + std::to_string(m));
  }
  if (m == 0) return;
  n_pushed_ += m;
  Equations(samples);
}

// The regressor rows of prepared samples, then the parallel filter's stage,
// or the fold.
void StreamedJointEquations::Equations(const JointLog& prepared) {
  const Eigen::Index m = prepared.t.size();
  const int n = n_dof_;
  // Regressor rows [W_0 τ_0 | W_1 τ_1 | … | t], the samples split over threads.
  regressor_.resize(m, width_ + 1);
  auto compute = [&](Eigen::Index r_begin, Eigen::Index r_end) {
    RobotData data(*model_);
    Eigen::MatrixXd Y;
    Eigen::VectorXd q(n), qd(n), qdd(n);
    // Rows are gathered in a row-major tile that stays in cache, then stored
    // column by column: a row stored straight into the column-major
    // regressor_ touches a cache line per entry.
    constexpr Eigen::Index kTile = 64;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tile(kTile, width_ + 1);
    for (Eigen::Index r0 = r_begin; r0 < r_end; r0 += kTile) {
      const Eigen::Index rows = std::min(kTile, r_end - r0);
      for (Eigen::Index i = 0; i < rows; ++i) {
        const Eigen::Index r = r0 + i;
        q = prepared.q.row(r).transpose();
        qd = prepared.qd.row(r).transpose();
        qdd = prepared.qdd.row(r).transpose();
        ComputeJointTorqueRegressor(*model_, friction_, q, qd, qdd, &data, &Y);
        for (int j = 0; j < n; ++j) {
          const std::vector<int>& cols = standard_[static_cast<size_t>(j)];
          const Eigen::Index o = offset_[static_cast<size_t>(j)], c = static_cast<Eigen::Index>(cols.size());
          for (Eigen::Index k = 0; k < c; ++k) tile(i, o + k) = Y(j, cols[static_cast<size_t>(k)]);
          tile(i, o + c) = prepared.tau(r, j);
        }
        tile(i, width_) = prepared.t[r];
      }
      regressor_.middleRows(r0, rows) = tile.topRows(rows);
    }
  };
  const Eigen::Index n_threads = std::min<Eigen::Index>(settings_.n_threads, std::max<Eigen::Index>(1, m / 64));
  {
    std::vector<std::jthread> threads;
    for (Eigen::Index p = 1; p < n_threads; ++p) threads.emplace_back(compute, p * m / n_threads, (p + 1) * m / n_threads);
    compute(0, m / n_threads);
  }
  if (!settings_.filter) {
    FoldRows(regressor_);
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
  // Columns split over the threads (each filtered on its own: the same result).
  {
    const Eigen::Index n_threads = settings_.n_threads;
    auto filter = [&](Eigen::Index c0, Eigen::Index c1) {
      FiltFiltWindow(sos_, n, w0 == 0, w0 + rows == n, filtered_.middleCols(c0, c1 - c0));
    };
    std::vector<std::jthread> threads;
    for (Eigen::Index p = 1; p < n_threads; ++p) threads.emplace_back(filter, p * width_ / n_threads, (p + 1) * width_ / n_threads);
    filter(0, width_ / n_threads);
  }
  const Eigen::Index m = (end - first + k - 1) / k;
  // Column by column (a row at a time would touch a cache line per entry).
  const Eigen::MatrixXd kept = filtered_(Eigen::seqN(first - w0, m, k), Eigen::all);
  FoldRows(kept);
}

namespace {
// τ − W β of one row [W_j τ_j] restricted to the joint's columns.
double RowResidual(const Eigen::Ref<const Eigen::RowVectorXd, 0, Eigen::InnerStride<>>& row, const std::vector<int>& columns,
                   const Eigen::VectorXd& beta) {
  const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
  double e = row[c];
  for (Eigen::Index k = 0; k < c; ++k) e -= row[k] * beta[columns[static_cast<size_t>(k)]];
  return e;
}
}  // namespace

void StreamedJointEquations::Replay(const RecordedEquationRows& rows) {
  if (n_pushed_ != 0 || !rows.replayable()) {
    throw std::invalid_argument("streamed equations: a replay needs a whole earlier pass's rows and nothing pushed");
  }
  for (const Eigen::MatrixXd& block : rows.blocks) FoldRows(block);
  n_pushed_ = settings_.n_samples;
}

// Folds equation rows [W_0 τ_0 | … | t] into the factors; records the series.
void StreamedJointEquations::FoldRows(const Eigen::Ref<const Eigen::MatrixXd>& rows) {
  const Eigen::Index m = rows.rows();
  if (RecordedEquationRows* record = settings_.record_rows; record && !record->overflowed) {
    const std::size_t bytes = static_cast<std::size_t>(rows.size()) * sizeof(double);
    if (record->bytes + bytes > record->max_bytes) {
      record->overflowed = true;
      record->blocks = {};
    } else {
      record->bytes += bytes;
      record->blocks.emplace_back(rows);
    }
  }
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
  // The scores s_t = Σ_j w_j² W_tjᵀ e_tj at the given fit, sample by sample.
  if (ScoreBatchMeans* scores = settings_.scores_into ? settings_.scores_into : scores_ ? &*scores_ : nullptr) {
    const LinearFit& fit = *settings_.score_fit;
    // Read through a row-major tile that stays in cache (a row of the
    // column-major rows touches a cache line per entry).
    constexpr Eigen::Index kTile = 64;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tile;
    for (Eigen::Index i0 = 0; i0 < m; i0 += kTile) {
      tile = rows.middleRows(i0, std::min(kTile, m - i0));
      for (Eigen::Index i = 0; i < tile.rows(); ++i) {
        score_.setZero();
        if (fit.score_offset.size() > 0) score_ = fit.score_offset;
        for (int j = 0; j < n_dof_; ++j) {
          const std::vector<int>& columns = factors_.joints[static_cast<size_t>(j)].columns;
          const Eigen::Index o = offset_[static_cast<size_t>(j)], c = static_cast<Eigen::Index>(columns.size());
          const double e = RowResidual(tile.row(i).segment(o, c + 1), columns, fit.beta);
          const double e_weights = fit.row_reweighting ? RowResidual(tile.row(i).segment(o, c + 1), columns,
                                                                     fit.row_reweighting->beta)
                                                       : e;
          const double w2e = ScoreRowWeight(fit, j, e_weights) * e;
          for (Eigen::Index k = 0; k < c; ++k) score_[columns[static_cast<size_t>(k)]] += w2e * tile(i, o + k);
        }
        scores->Push(score_);
      }
    }
  }
  if (!settings_.fold) return;
  // Each joint's factor on its own, the joints dealt round the threads.
  auto fold = [&](int first) {
    for (int j = first; j < n_dof_; j += settings_.n_threads) {
      const Eigen::Index o = offset_[static_cast<size_t>(j)];
      const Eigen::Index c = static_cast<Eigen::Index>(standard_[static_cast<size_t>(j)].size());
      Eigen::MatrixXd& f = fold_[static_cast<size_t>(j)];
      f = rows.middleCols(o, c + 1);
      if (settings_.row_weights) {  // an IRLS pass: each row scaled by √w at its residual
        const std::vector<int>& columns = factors_.joints[static_cast<size_t>(j)].columns;
        Eigen::VectorXd r(f.rows());
        for (Eigen::Index i = 0; i < f.rows(); ++i) r[i] = RowResidual(f.row(i), columns, settings_.row_weights->beta);
        if (settings_.residuals) settings_.residuals->AddRows(j, r, f.leftCols(c), columns, *settings_.row_weights);
        for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) *= std::sqrt(settings_.row_weights->Weight(j, r[i]));
      }
      FoldJointRows(f, &factors_.joints[static_cast<size_t>(j)]);
    }
  };
  std::vector<std::jthread> threads;
  for (int t = 1; t < std::min(settings_.n_threads, n_dof_); ++t) threads.emplace_back(fold, t);
  fold(0);
}

}  // namespace idbench
