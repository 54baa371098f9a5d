#include "idbench/ident/log_identification.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "idbench/ident/prepared_log_equations.h"

namespace idbench {

namespace {

// Iterates the closed-loop estimator (iv, didim) from the OLS estimate on the
// samples the fit used (every sample: the controller's period), then puts its
// estimate, σ and fit in *out.
void EstimateInClosedLoop(const RobotModel& model, const JointTorqueOptions& options, const PreparedLog& log,
                          const ClosedLoopInputs& inputs, LogIdentification* out) {
  const std::string name(ToString(options.estimator));
  if (log.log.n_samples() != log.n_raw) {
    throw std::invalid_argument("estimator " + name + ": the log has " + std::to_string(log.n_raw) +
                                " samples, more than the " + std::to_string(LogPreparationOptions::kMaxHeldSamples) +
                                " held for a re-simulated estimator");
  }
  const std::vector<Eigen::Index> kept = StackedSamples(log.log, log.parallel_filter);
  if (kept.empty() || kept.back() - kept.front() + 1 != static_cast<Eigen::Index>(kept.size())) {
    throw std::invalid_argument("estimator " + name + ": the re-simulated estimators use every sample (the "
                                "controller's period): no decimation");
  }
  const JointLog& all = log.log;
  const Eigen::Index first = kept.front(), n = static_cast<Eigen::Index>(kept.size());
  JointLog used;
  used.t = all.t.segment(first, n);
  used.q = all.q.middleRows(first, n);
  used.tau = all.tau.middleRows(first, n);
  if (all.has_derivatives()) {
    used.qd = all.qd.middleRows(first, n);
    used.qdd = all.qdd.middleRows(first, n);
  }
  ClosedLoopEstimatorOptions estimator;
  estimator.method = options.estimator == TorqueEstimator::kDidim ? ClosedLoopMethod::kDidim
                                                                   : ClosedLoopMethod::kInstrumentalVariables;
  estimator.controller = inputs.controller;
  estimator.torque_held = log.torque_held;
  JointTorqueIdentification& id = out->identification;
  // From OLS; when its estimate is no mechanism (its mass matrix not positive
  // definite: it cannot be simulated), from the physically consistent one,
  // which is by construction.
  ClosedLoopEstimate estimate =
      EstimateClosedLoop(model, options.friction, id.base, used, *inputs.reference, id.linear.beta, estimator);
  if (!estimate.converged && estimate.iterations == 0) {
    estimate = EstimateClosedLoop(model, options.friction, id.base, used, *inputs.reference, id.consistent.beta,
                                  estimator);
    estimate.message = "from the physically consistent estimate (OLS's mass matrix is not positive definite): " +
                       estimate.message;
  }
  id.beta = estimate.beta;
  id.linear.sigma = estimate.sigma;
  id.linear.sigma_white = estimate.sigma_white;
  id.linear.covariance_method = estimate.covariance;
  id.fit = PredictTorques(out->factors, estimate.beta);
  // The robot model to load: the consistent estimate nearest this one, not least squares'.
  if (estimate.converged) CentreConsistentFit(model, out->factors, options, estimate.beta, &id);
  if (!estimate.converged) out->warnings.push_back("estimator " + name + ": " + estimate.message);
  out->closed_loop = estimate;
}

}  // namespace

void CheckClosedLoopLogCount(TorqueEstimator estimator, size_t n_logs) {
  if (!IsClosedLoopEstimator(estimator) || n_logs <= 1) return;
  throw std::invalid_argument("estimator " + std::string(ToString(estimator)) + ": one data log (it re-simulates "
                              "the closed loop along one reference), got " + std::to_string(n_logs));
}

LogIdentification IdentifyFromLogs(const RobotModel& model, const std::vector<const PreparedLog*>& data,
                                   const JointTorqueOptions& options_in, const ClosedLoopInputs* closed_loop,
                                   const LogStageObserver& stage) {
  if (data.empty()) throw std::invalid_argument("data: expected at least one log");
  auto next = [&](const std::string& name) { return stage ? stage(name) : nullptr; };
  const std::string estimator_name(ToString(options_in.estimator));
  const bool re_simulated = IsClosedLoopEstimator(options_in.estimator);
  CheckClosedLoopLogCount(options_in.estimator, data.size());
  if (re_simulated && (!closed_loop || !closed_loop->reference)) {
    throw std::invalid_argument("estimator " + estimator_name + ": re-simulates the closed loop: it needs the "
                                "robot's controller and the reference it tracked");
  }
  JointTorqueOptions options = options_in;
  options.parallel_filter = data.front()->parallel_filter;

  // The equations streamed into factors, each log's in turn stacked onto the
  // first's (MergeStackedFactors), then solved.
  // The first pass's rows are held (within kMaxRecordedEquationBytes) for
  // the later ones to replay.
  LogIdentification out;
  const BaseParameters base = ComputeBaseParameters(model, options.friction, options.base);
  std::vector<RecordedEquationRows> rows(data.size());
  for (RecordedEquationRows& r : rows) r.max_bytes = kMaxRecordedEquationBytes / data.size();
  for (size_t i = 0; i < data.size(); ++i) {
    const PreparedLog& log = *data[i];
    StackedFactors own = FoldPreparedLog(log, model, options.friction, base, {}, nullptr,
                                         LogPreparationOptions::kMaxHeldSamples,
                                         next("identifying from " + log.path), nullptr, nullptr, &rows[i]);
    out.n_kept.push_back(own.n_samples());
    if (data.size() > 1) out.cond.push_back(SolveOls(own).cond);
    if (i == 0) {
      out.factors = std::move(own);
    } else {
      MergeStackedFactors(own, &out.factors);
    }
  }
  // IRLS reads the logs again (or their held rows) for each of its passes
  // (each folded on its own, then stacked).
  const StreamObserver* solving = next("solving (" + estimator_name + ")");
  const ReweightedFold reweighted_fold = [&](const RobustRowWeights& weights, IrlsPassRecord* residuals) {
    StackedFactors all;
    for (size_t i = 0; i < data.size(); ++i) {
      StackedFactors own = FoldPreparedLog(*data[i], model, options.friction, base, {}, nullptr,
                                           LogPreparationOptions::kMaxHeldSamples, solving, &weights, residuals,
                                           &rows[i]);
      if (i == 0) {
        all = std::move(own);
      } else {
        MergeStackedFactors(own, &all);
      }
    }
    return all;
  };
  out.identification = IdentifyJointTorque(model, base, out.factors, options, &reweighted_fold);
  // σ from the residual as it is: the logs streamed again for the scores at β̂.
  LinearFit& linear = out.identification.linear;
  if (data.size() == 1) {
    ApplyPreparedLogScoreCovariance(*data.front(), model, options.friction, base, &linear,
                                    next("sigma from the residual of " + data.front()->path), &rows.front());
  } else {
    ApplyPreparedLogsScoreCovariance(
        data, out.n_kept, model, options.friction, base, &linear,
        [&](const PreparedLog& log) { return next("sigma from the residual of " + log.path); }, &rows);
  }
  rows = {};
  if (re_simulated) {
    next("re-simulating the closed loop (" + estimator_name + ")");
    EstimateInClosedLoop(model, options, *data.front(), *closed_loop, &out);
  }
  if (!linear.solve.converged) {
    out.warnings.push_back("estimator " + estimator_name + ": " + linear.solve.message +
                           "; its beta and sigma are those of where it stopped");
  }
  // Actuator-side columns scale as N and N² with the gear ratios N, the link
  // ones do not: from N = 1000 (N² = 1e6, the fit's rank tolerance) a column
  // may be lost to that spread rather than to the motion. Said when it happens.
  if (options.friction.actuator_side() && linear.rank < base.n_base()) {
    const double ratio = options.friction.actuator_from_joint.cwiseAbs().maxCoeff();
    if (ratio >= 1e3) {
      char text[600];
      std::snprintf(text, sizeof(text),
                    "the transmission's gear ratios, up to %g, make the actuator-side columns (∝ N, N²) up to %.3g times "
                    "the link columns; W has rank %d of %d, and the %d base parameter(s) marked 'not ident.' may be "
                    "lost to that scale rather than to the motion (the fit resolves 1e-6 of the largest): check "
                    "with friction_side joint, or the transmission's ratios",
                    ratio, ratio * ratio, linear.rank, base.n_base(),
                    static_cast<int>(std::count(linear.identifiable.begin(), linear.identifiable.end(), false)));
      out.warnings.push_back(text);
    }
  }
  return out;
}

}  // namespace idbench
