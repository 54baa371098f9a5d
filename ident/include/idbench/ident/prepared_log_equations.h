// A prepared log's equations (logs/joint_log_pipeline.h gives the samples):
// streamed through the regressor, parallel-filtered and folded into the
// triangular factors a fit solves (StreamedJointEquations), and streamed again
// for σ from the residual as it is (batch means). Memory does not grow with
// the log's length.
#pragma once

#include <functional>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/streamed_joint_equations.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

// What an identification holds of its logs' equation rows for its later
// passes (RecordedEquationRows), over all its logs: 64 MiB, e.g. 100 000
// kept samples of a 6-joint arm with ~80 columns per row. Longer logs are
// streamed on every pass.
inline constexpr std::size_t kMaxRecordedEquationBytes = std::size_t{64} << 20;

// Streams a prepared log's equations for `base` into factors: the source
// read again in chunks of kStreamBlockSamples, filtered, the regressor
// stacked, parallel-filtered and folded (StreamedJointEquations). With
// series_beta (n_base), *series gets the measured and predicted torques of
// at most max_series_points kept equations (every k-th; all when fewer).
// With row_weights, an IRLS pass (StreamedEquationsSettings::row_weights).
// With rows: when they hold an earlier pass's (RecordedEquationRows), those
// are folded instead of the log; else this pass records them (within their
// max_bytes).
// A progress line goes to stderr when the work takes more than a few
// seconds (and to the observer, if any: StreamStopped once its stop is
// set). Throws std::invalid_argument naming the path for too few equations
// and the source's errors.
StackedFactors FoldPreparedLog(const PreparedLog& log, const RobotModel& model, const FrictionModel& friction,
                               const BaseParameters& base, const Eigen::VectorXd& series_beta = {},
                               TorqueSeries* series = nullptr,
                               Eigen::Index max_series_points = LogPreparationOptions::kMaxHeldSamples,
                               const StreamObserver* observer = nullptr,
                               const RobustRowWeights* row_weights = nullptr, IrlsPassRecord* residuals = nullptr,
                               RecordedEquationRows* rows = nullptr);

// σ from the residual as it is: the prepared log's equations streamed again
// (as FoldPreparedLog, without folding them), each kept sample's score at
// the fit's β̂ summed over blocks (StreamedEquationsSettings::score_fit),
// then fit's covariance replaced by the batch-means sandwich
// (ApplyScoreCovariance). Memory O(n_base²) beside the stream's blocks.
// Progress, errors and rows as FoldPreparedLog.
void ApplyPreparedLogScoreCovariance(const PreparedLog& log, const RobotModel& model, const FrictionModel& friction,
                                     const BaseParameters& base, LinearFit* fit,
                                     const StreamObserver* observer = nullptr, RecordedEquationRows* rows = nullptr);

// The same for a fit to several logs stacked (IdentifyOptions::more_data):
// the logs streamed one after the other, n_kept[i] the samples log i's fold
// kept (StackedFactors::n_samples), into one batch-means accumulator whose
// blocks never straddle two logs (ScoreBatchMeans::EndSeries): the logs are
// separate series, independent of each other. observer(log) gives each
// pass's observer (may be empty, or return nullptr); rows, if given, one
// per log. Throws std::invalid_argument unless there is a count (and rows)
// per log, and as FoldPreparedLog.
void ApplyPreparedLogsScoreCovariance(const std::vector<const PreparedLog*>& logs,
                                      const std::vector<Eigen::Index>& n_kept, const RobotModel& model,
                                      const FrictionModel& friction, const BaseParameters& base, LinearFit* fit,
                                      const std::function<const StreamObserver*(const PreparedLog&)>& observer = {},
                                      std::vector<RecordedEquationRows>* rows = nullptr);

}  // namespace idbench
