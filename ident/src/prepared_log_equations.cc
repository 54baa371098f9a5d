#include "idbench/ident/prepared_log_equations.h"

#include <stdexcept>
#include <string>

namespace idbench {

namespace {

// One pass of `equations` over the log: rows held by an earlier pass
// replayed, else the log streamed (and its rows recorded, within their bound).
void PassOverLog(const PreparedLog& log, StreamedJointEquations* equations, RecordedEquationRows* rows,
                 const char* what, const StreamObserver* observer) {
  if (rows && rows->replayable()) {
    equations->Replay(*rows);
    return;
  }
  StreamPreparedSamples(log, [&](const JointLog& prepared, Eigen::Index) { equations->Push(prepared); }, what,
                        observer);
  if (!equations->done()) throw std::logic_error(log.path + ": the log ended early");
  if (rows && !rows->overflowed) rows->complete = true;
}

// The settings' record_rows for a pass: rows to fill when they hold nothing yet.
RecordedEquationRows* RowsToRecord(RecordedEquationRows* rows) {
  if (!rows || rows->replayable() || rows->overflowed) return nullptr;
  rows->blocks.clear();
  rows->bytes = 0;
  return rows;
}

}  // namespace

StackedFactors FoldPreparedLog(const PreparedLog& log, const RobotModel& model, const FrictionModel& friction,
                               const BaseParameters& base, const Eigen::VectorXd& series_beta, TorqueSeries* series,
                               Eigen::Index max_series_points, const StreamObserver* observer,
                               const RobustRowWeights* row_weights, IrlsPassRecord* residuals,
                               RecordedEquationRows* rows) {
  StreamedEquationsSettings settings;
  settings.filter = log.parallel_filter;
  settings.n_samples = log.n_samples;
  settings.row_weights = row_weights;
  settings.residuals = residuals;
  settings.record_rows = RowsToRecord(rows);
  if (series) {
    settings.series_beta = series_beta;
    settings.series_max_points = max_series_points;
  }
  try {
    StreamedJointEquations equations(model, friction, base, settings);
    PassOverLog(log, &equations, rows, "identifying", observer);
    if (equations.factors().n_samples() * model.n_dof() <= base.n_base()) {
      throw std::invalid_argument("joint log has " + std::to_string(equations.factors().n_samples()) +
                                  " usable samples (" + std::to_string(equations.factors().n_samples() * model.n_dof()) +
                                  " equations) for " + std::to_string(base.n_base()) +
                                  " base parameters; record more samples");
    }
    if (series) *series = equations.series();
    return equations.factors();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.rfind(log.path + ":", 0) == 0) throw;
    throw std::invalid_argument(log.path + ": " + what);
  }
}

namespace {

// One pass over a prepared log for the scores at *fit (into `into`, or the
// pass's own accumulator when null), then `done` with the pass's equations.
void StreamLogScores(const PreparedLog& log, const RobotModel& model, const FrictionModel& friction,
                     const BaseParameters& base, const LinearFit* fit, ScoreBatchMeans* into,
                     const StreamObserver* observer, RecordedEquationRows* rows,
                     const std::function<void(const StreamedJointEquations&)>& done) {
  StreamedEquationsSettings settings;
  settings.filter = log.parallel_filter;
  settings.n_samples = log.n_samples;
  settings.score_fit = fit;
  settings.scores_into = into;
  settings.fold = false;
  settings.record_rows = RowsToRecord(rows);
  try {
    StreamedJointEquations equations(model, friction, base, settings);
    PassOverLog(log, &equations, rows, "sigma from the residual", observer);
    done(equations);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.rfind(log.path + ":", 0) == 0) throw;
    throw std::invalid_argument(log.path + ": " + what);
  }
}

}  // namespace

void ApplyPreparedLogScoreCovariance(const PreparedLog& log, const RobotModel& model, const FrictionModel& friction,
                                     const BaseParameters& base, LinearFit* fit, const StreamObserver* observer,
                                     RecordedEquationRows* rows) {
  StreamLogScores(log, model, friction, base, fit, nullptr, observer, rows, [&](const StreamedJointEquations& equations) {
    if (!equations.scores()->done()) throw std::logic_error(log.path + ": the log ended early");
    ApplyScoreCovariance(*equations.scores(), fit);
  });
}

void ApplyPreparedLogsScoreCovariance(const std::vector<const PreparedLog*>& logs,
                                      const std::vector<Eigen::Index>& n_kept, const RobotModel& model,
                                      const FrictionModel& friction, const BaseParameters& base, LinearFit* fit,
                                      const std::function<const StreamObserver*(const PreparedLog&)>& observer,
                                      std::vector<RecordedEquationRows>* rows) {
  if (logs.empty() || logs.size() != n_kept.size() || (rows && rows->size() != logs.size())) {
    throw std::invalid_argument("sigma of several logs: expected one kept-sample count per log, got " +
                                std::to_string(n_kept.size()) + " for " + std::to_string(logs.size()) + " logs");
  }
  Eigen::Index total = 0;
  for (Eigen::Index n : n_kept) total += n;
  // One accumulator: the block length from all samples, a series per log.
  ScoreBatchMeans scores(static_cast<int>(base.n_base()), total);
  for (size_t i = 0; i < logs.size(); ++i) {
    StreamLogScores(*logs[i], model, friction, base, fit, &scores, observer ? observer(*logs[i]) : nullptr,
                    rows ? &(*rows)[i] : nullptr, [](const StreamedJointEquations&) {});
    if (i + 1 < logs.size()) scores.EndSeries();
  }
  if (!scores.done()) throw std::logic_error("sigma of several logs: fewer kept samples than their folds counted");
  ApplyScoreCovariance(scores, fit);
}

}  // namespace idbench
