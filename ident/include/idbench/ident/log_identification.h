// Joint-torque identification from prepared logs (logs/joint_log_pipeline.h),
// one or several of one robot: each log's equations streamed and folded
// (prepared_log_equations.h), stacked, solved by the chosen estimator, σ from
// the residual as it is (the logs streamed again), and for the closed-loop
// estimators (iv, didim) the iteration that re-simulates the loop. Memory does
// not grow with the logs' length, except for the closed-loop estimators,
// which re-simulate the held log (at most LogPreparationOptions::kMaxHeldSamples).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/joint_controller.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/ident/closed_loop_estimators.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench {

// What a closed-loop estimator re-simulates: the robot's controller and the
// reference it tracked during the experiment.
struct ClosedLoopInputs {
  JointControllerOptions controller;
  const Trajectory* reference = nullptr;
};

// Each stage of the work, named for the user ("identifying from PATH",
// "solving (ols)", "sigma from the residual of PATH", "re-simulating the
// closed loop (iv)"), is announced before it starts; the observer returned
// (may be nullptr) sees its passes' progress and may stop them (StreamStopped).
using LogStageObserver = std::function<const StreamObserver*(const std::string& stage)>;

struct LogIdentification {
  JointTorqueIdentification identification;  // beta, σ, fit; of the closed-loop estimate when there is one
  StackedFactors factors;                    // every log's equations, stacked
  std::vector<Eigen::Index> n_kept;          // the equations' samples each log kept, in order
  std::vector<double> cond;                  // each log's own cond(W) (several logs only)
  std::optional<ClosedLoopEstimate> closed_loop;
  std::vector<std::string> warnings;         // for stderr: an estimator that did not converge, a lost column
};

// Identifies the robot from `data` (at least one log, in order; the first
// log's parallel filter is options.parallel_filter's, which is ignored).
// closed_loop: required by the closed-loop estimators (one log only), ignored
// by the others. Throws std::invalid_argument for too few equations, the
// sources' errors (naming the log), several logs with a closed-loop
// estimator, a decimated or longer-than-held log for one; StreamStopped once
// a stage's observer says stop.
// Throws std::invalid_argument when `estimator` re-simulates the closed loop
// (iv, didim) and is given more than one log: it follows one reference.
void CheckClosedLoopLogCount(TorqueEstimator estimator, size_t n_logs);

LogIdentification IdentifyFromLogs(const RobotModel& model, const std::vector<const PreparedLog*>& data,
                                   const JointTorqueOptions& options, const ClosedLoopInputs* closed_loop = nullptr,
                                   const LogStageObserver& stage = {});

}  // namespace idbench
