// The workbench's plots, built from experiment results (drawn by
// idbench/render/plot.h): joint signals over time, measured versus predicted
// torques, identified versus true parameters, singular-value spectra, and a
// comparison of motions.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/per_body_identifier.h"
#include "idbench/render/plot.h"
#include "idbench/workbench/commands/benchmark_command.h"

namespace idbench {

// Joint signals sampled for plotting: rows are samples, columns joints.
struct JointSignals {
  std::vector<double> t;  // [s] (n_samples)
  Eigen::MatrixXd q;      // [rad]
  Eigen::MatrixXd qd;     // [rad/s]
  Eigen::MatrixXd qdd;    // [rad/s²]
  Eigen::MatrixXd tau;    // [N m]
};

// Every k-th sample so that at most max_samples remain.
JointSignals SignalsOf(const SimulationLog& log, int max_samples = 2000);
JointSignals SignalsOf(const JointLog& log, int max_samples = 2000);

// q, qd, qdd and τ over time, one axes each, one line per joint, the lines
// labelled by joint name (the robot file's; none: "joint 1", "joint 2", …).
PlotFigure JointSignalsPlot(const JointSignals& signals, const std::vector<std::string>& joint_names = {});

// The words of a torque comparison plot.
struct TorquePlotLabels {
  std::string log = "identification log";  // in each axes' title
  std::string measured = "measured";       // the log's torque ("simulated" for a simulation's)
  std::vector<std::string> joint_names;    // the robot file's; none: "joint 1", "joint 2", …
};

// Measured against predicted torque (PredictTorqueSeries) over time, one axes
// per joint in two columns, titled "<joint name>, <labels.log>", each with the
// lines labels.measured and "predicted", τ [N m] against t [s] with ticks on
// both axes; every k-th sample so that at most max_samples remain, as SignalsOf.
PlotFigure TorqueComparisonPlot(const TorqueSeries& series, const TorquePlotLabels& labels = {},
                                int max_samples = 2000);

// The robot file's joint names, in chain order (n_dof).
std::vector<std::string> JointNames(const RobotModel& model);

// The name of joint j (0-based) in a plot: joint_names[j], or "joint j+1"
// when it has none.
std::string JointLabel(const std::vector<std::string>& joint_names, Eigen::Index j);

// One parameter: its true (or reference) value, the estimate and its
// uncertainty (σ, or the error when there is no σ); NaN estimate = not identified.
struct ParameterEstimate {
  std::string name;
  double reference = 0.0;
  double estimate = 0.0;
  double error_bar = 0.0;
};

// Reference and estimate per parameter, the estimate with ± error bars; a log
// axis when every value is positive.
PlotFigure ParameterPlot(const std::string& title, const std::string& reference_label,
                         const std::vector<ParameterEstimate>& parameters);

// The per-body run's parameters (true vs identified, error bars = |error|).
std::vector<ParameterEstimate> RunParameterEstimates(const PerBodyIdentificationResult& result);

// Singular values of one or more column-normalised regressors, largest first,
// on a log axis (zeros are left out: they are the unidentifiable directions).
struct Spectrum {
  std::string label;
  Eigen::VectorXd singular_values;
};
PlotFigure SpectrumPlot(const std::string& title, const std::vector<Spectrum>& spectra);

// Singular values of A with every column scaled to unit norm; columns below
// 1e-9 of the largest norm count as zero.
Eigen::VectorXd NormalizedSingularValues(const Eigen::MatrixXd& A);

// The Euler (inertia) block of every body, stacked over the samples of a run:
// the matrix whose conditioning decides J11, J22, J33.
std::vector<Spectrum> RunEulerSpectra(const RobotModel& model, const SimulationLog& log,
                                      const std::vector<int>& steps);

// How well motions excite: cond, log10 det(KᵀK) and the largest relative
// error, as bars per motion.
struct MotionSummary {
  std::string name;
  double cond = 0.0;         // worst cond over the blocks
  double log10_det = 0.0;    // Σ log10 det(KᵀK) over the blocks' identifiable columns
  double max_rel_error = 0.0;
};
struct MotionPlotTitles {
  std::string cond = "cond (worst block)";
  std::string log_det = "log10 det(KᵀK)";
  std::string error = "largest relative error";
};
PlotFigure MotionComparisonPlot(const std::vector<MotionSummary>& motions, const MotionPlotTitles& titles = {});

// A motion's summary from its spectra (cond and log det) and the result.
MotionSummary SummarizeMotion(const std::string& name, const std::vector<Spectrum>& spectra, double max_rel_error);

// Quartiles of values (any order; NaN left out) by linear interpolation
// between order statistics (Hyndman & Fan's type 7, R's and NumPy's default):
// q(p) = x_(⌊h⌋) + (h − ⌊h⌋)(x_(⌊h⌋+1) − x_(⌊h⌋)), h = (n − 1) p. Whiskers reach
// the farthest values within 1.5 IQR of the box (Tukey); the others are
// outliers. All NaN when no value is finite.
struct BoxSummary {
  double q1 = 0.0, median = 0.0, q3 = 0.0;
  double whisker_low = 0.0, whisker_high = 0.0;
  std::vector<double> outliers;
};
BoxSummary SummarizeBox(std::vector<double> values);

// The benchmark's parameter errors as box plots, one panel per noise preset,
// one box per estimator (log scale: the closed-loop estimators' tails span
// decades); diverged trials are left out as in the table.
PlotFigure BenchmarkErrorPlot(const BenchmarkResult& result);

}  // namespace idbench
