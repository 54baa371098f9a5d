// Joint-torque equations of a long log folded as its prepared samples arrive
// (issue 24): the base regressor, the parallel filter of W and τ
// (ParallelFilterStackedRows) with its trimming and decimation run in
// overlapping windows (OverlapWindows, FiltFiltWindow), and the fold into
// per-joint triangular factors (StackedFactors). With StreamedLogFilter in
// front, a log's qd, qdd estimated the same way: memory is
// O(n_base² + kStreamBlockSamples · n_base), independent of the log's length,
// and the factors equal those of the whole-log path (ProcessJointLog,
// StackEquations, FactorStackedRows) to rounding and the filters' 1e-12
// settling.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/logs/overlap_windows.h"
#include "idbench/ident/residual_covariance.h"
#include "idbench/logs/signal_filter.h"
#include "idbench/logs/streamed_log_filter.h"

namespace idbench {

// The equation rows a pass folded (filtered, trimmed, decimated: what
// FoldRows sees), held so that later passes over the same log (IRLS's, the
// scores') replay them instead of reading, filtering and regressing the log
// again: the same rows in the same blocks, so the same sums to the bit.
// Bounded: once the rows would pass max_bytes they are dropped and every
// pass streams the log as before.
struct RecordedEquationRows {
  std::size_t max_bytes = 0;
  std::vector<Eigen::MatrixXd> blocks;
  std::size_t bytes = 0;
  bool overflowed = false;
  bool complete = false;  // a whole pass's rows are held (set by the pass's owner)
  bool replayable() const { return complete && !overflowed; }
};

struct StreamedEquationsSettings {
  // The parallel filter of W and τ at the log's uniform rate; nullopt: every
  // sample's equations are folded as they are.
  std::optional<ParallelFilter> filter;
  Eigen::Index n_samples = 0;            // samples that will be pushed
  int n_threads = 0;                     // regressor threads; 0: the hardware's
  Eigen::Index block = kStreamBlockSamples;
  // Optional, bounded: with series_beta, every series_stride-th kept
  // equation's t, τ and W β (both parallel-filtered when filtered).
  Eigen::VectorXd series_beta;  // empty: no series
  Eigen::Index series_stride = 1;
  Eigen::Index series_max_points = 0;  // > 0: the stride raised to keep at most this many
  // Optional, O(n_base²): with score_fit (a fit to these equations, e.g. of
  // the factors of a first pass), every kept sample's score
  // s_t = Σ_j w_j² W_tjᵀ (τ_tj − W_tj β̂) summed over blocks of
  // score_block_samples (0: ⌈√n_kept⌉) for its batch-means covariance
  // (residual_covariance.h).
  const LinearFit* score_fit = nullptr;
  Eigen::Index score_block_samples = 0;
  // With score_fit: the scores go into this (announced for every log fitted
  // together, one after the other: ScoreBatchMeans::EndSeries between them)
  // instead of this log's own (scores() is then nullptr). Not owned.
  ScoreBatchMeans* scores_into = nullptr;
  bool fold = true;  // false: the factors are left empty (a pass for the scores or the series only)
  // Optional: an IRLS pass (reweighted_least_squares.h): each folded row
  // scaled by √w at its residual, which is added to *residuals (if given;
  // rows of one joint from one thread).
  const RobustRowWeights* row_weights = nullptr;
  IrlsPassRecord* residuals = nullptr;
  // Optional: the folded rows appended here (within its max_bytes). Not owned.
  RecordedEquationRows* record_rows = nullptr;
};

class StreamedJointEquations {
 public:
  // Throws std::invalid_argument for a filter the log is too short for
  // (FiltFiltMinSamples), too few samples to trim, or n_samples < 1.
  StreamedJointEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                         const StreamedEquationsSettings& settings);

  // The log's next prepared samples, in order (t uniform at the filter's rate
  // when filtered; q, qd, qdd, tau of n_dof columns). Throws
  // std::invalid_argument on a shape mismatch or more samples than announced.
  void Push(const JointLog& samples);

  // Instead of Push: the rows of an earlier pass over the same log, with the
  // same filter (rows.replayable()); done() after it. Throws
  // std::invalid_argument unless nothing was pushed and the rows are whole.
  void Replay(const RecordedEquationRows& rows);

  bool done() const { return n_pushed_ == settings_.n_samples; }
  // The folded equations; complete once done().
  const StackedFactors& factors() const { return factors_; }
  const TorqueSeries& series() const { return series_; }
  // The scores' block sums (settings.score_fit); nullptr without score_fit
  // or with scores_into.
  const ScoreBatchMeans* scores() const { return scores_ ? &*scores_ : nullptr; }

 private:
  void Equations(const JointLog& prepared);
  void FoldWindow(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0, Eigen::Index o1);
  void FoldRows(const Eigen::Ref<const Eigen::MatrixXd>& rows);

  const RobotModel* model_;
  FrictionModel friction_;
  const BaseParameters* base_;
  StreamedEquationsSettings settings_;
  int n_dof_;
  std::vector<std::vector<int>> standard_;  // per joint: standard column of each factor column
  std::vector<Eigen::Index> offset_;        // per joint: first column of its [W_j τ_j] in a regressor row
  Eigen::Index width_ = 0;                  // Σ (c_j + 1)
  SosMatrix sos_;
  Eigen::Index trim_ = 0;
  std::optional<OverlapWindows> rows_;  // the parallel filter's windows
  Eigen::Index n_pushed_ = 0;
  Eigen::MatrixXd filtered_, regressor_;  // workspace
  std::vector<Eigen::MatrixXd> fold_;     // per joint
  StackedFactors factors_;
  Eigen::Index n_series_kept_ = 0;
  TorqueSeries series_;
  std::optional<ScoreBatchMeans> scores_;
  Eigen::VectorXd score_;  // workspace (n_base)
};

}  // namespace idbench
