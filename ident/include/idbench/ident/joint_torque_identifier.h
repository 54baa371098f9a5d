// Joint-torque identification of a serial robot from a joint log (Gautier &
// Khalil's method, as used on real robots): stack the base regressor over the
// log's samples, then estimate the base parameters by OLS, WLS, or a
// physically consistent fit.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "idbench/engine/enum_names.h"
#include "idbench/engine/measurements.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/ident/physically_consistent.h"
#include "idbench/ident/plausible_fit.h"
#include "idbench/ident/reweighted_least_squares.h"
#include "idbench/logs/signal_filter.h"

namespace idbench {

// ols: least squares; wls: joints weighted by their noise; pc: physically
// consistent (plausible_fit.h); tls: total least squares, the regressor noisy
// too (total_least_squares.h); irls: iteratively reweighted, robust to
// outliers (reweighted_least_squares.h). kInstrumentalVariables and kDidim
// are the closed-loop estimators (closed_loop_estimators.h):
// IdentifyJointTorque gives their starting point, OLS, and the front end
// iterates from it with the controller and reference.
enum class TorqueEstimator { kOls, kWls, kPhysicallyConsistent, kTls, kIrls, kInstrumentalVariables, kDidim };
inline constexpr EnumNames<TorqueEstimator, 7> kTorqueEstimatorNames{
    "estimator", {"ols", "wls", "pc", "tls", "irls", "iv", "didim"}};

// "ols", "wls", "pc", "tls", "irls", "iv", "didim".
std::string_view ToString(TorqueEstimator estimator);
// Whether the estimator re-simulates the closed loop (iv, didim).
bool IsClosedLoopEstimator(TorqueEstimator estimator);
// false with *why = "estimator: expected ols, wls, pc, tls, irls, iv or didim, got '...'".
bool ParseTorqueEstimator(std::string_view text, TorqueEstimator* estimator, std::string* why = nullptr);

// What makes the physically consistent estimate a robot description one can
// load, relative to the robot file (plausible_fit.h): bounds and the weight of
// the prior.
struct PlausibilitySettings {
  // Each link's mass within [mass_factor_min, mass_factor_max] × the file's.
  double mass_factor_min = 0.5;
  double mass_factor_max = 1.5;
  double total_mass = 0.0;              // [kg] of the moving links; 0: no bound beyond the links'
  double total_mass_tolerance = 0.1;    // Σ m within total_mass × (1 ± this)
  bool com_in_geometry = true;          // centre of mass in the box around the link's shapes
  double prior_weight = 1e-4;           // γ (plausible_fit.h)
  // The physically consistent estimate is a robot model only when its cost
  // ‖W_b β − τ‖² is within this fraction above the OLS optimum (see
  // IdentificationVerdict). Real logs carry effects no model holds, which
  // OLS absorbs into unphysical values: the KUKA LWR4+'s plausible fit costs
  // +28.6 % and predicts its held-out log better (5.4 % against OLS's
  // 12.7 %); bounds that contradict the data cost far more (the Stäubli
  // TX40's file: +2530 %).
  double cost_tolerance = 0.5;

  bool IsValid(std::string* why) const;
  // Also checks the settings against the robot: the total mass's range must
  // meet the range the links' bounds allow.
  bool IsValidFor(const RobotModel& model, std::string* why) const;
};

struct JointTorqueOptions {
  FrictionModel friction{.viscous = true, .coulomb = true};
  std::optional<ParallelFilter> parallel_filter;
  TorqueEstimator estimator = TorqueEstimator::kOls;
  // σ of the least-squares estimate: kBatchMeans from the residual as it is
  // (residual_covariance.h), kWhite as if it were white. Used by the
  // identification from a log; from factors, σ is white (the scores need a
  // second pass over the rows: StreamedEquationsSettings::score_fit).
  CovarianceMethod covariance = CovarianceMethod::kBatchMeans;
  BaseParameterOptions base;
  PlausibilitySettings plausibility;
  IrlsOptions irls;  // estimator irls
};

// The bounds and scales of the plausible fit for a robot file (the prior):
// per link, mass in the settings' range, centre of mass in LinkBoundingBox_B
// grown to hold the file's own centre of mass (links without shapes: unbounded; links whose own centre of mass the box
// contradicts, CheckCenterOfMassInGeometry: unbounded, with
// com_outside_geometry set), scales D_m = m, D_h = m L, D_I = m L²
// with L the link's size (half the box diagonal, at least |c| and 5 cm),
// friction scales max(|value|, 1); Fv, Fc, Ia ≥ 0.
PlausibleFitOptions MakePlausibleFitOptions(const RobotModel& model, const FrictionModel& friction,
                                            const PlausibilitySettings& settings);

// Whether the physically consistent estimate, what a robot description
// (URDF, friction) is written from whatever the estimator, is fit to load.
enum class ModelVerdict {
  kFitToLoad,         // converged, and its cost within cost_tolerance of the OLS optimum
  kNotConverged,      // the solver stopped before certifying its optimum
  kCostAboveOptimum,  // converged, but its bounds hold the cost above the OLS optimum by more than cost_tolerance
};
// "fit to load", "not converged", "cost above the optimum".
const char* ToString(ModelVerdict verdict);
// "fit_to_load", "not_converged", "cost_above_optimum" (identified.json).
const char* ToKey(ModelVerdict verdict);

struct IdentificationVerdict {
  ModelVerdict status = ModelVerdict::kFitToLoad;
  // (cost − OLS cost) / max(OLS cost, 10⁻¹⁰ ‖τ‖²): the floor keeps a
  // noise-free log (OLS cost ~ rounding) from counting rounding as excess.
  double cost_excess = 0.0;
  double cost_tolerance = 0.5;  // PlausibilitySettings::cost_tolerance
  std::string message;  // one line: converged or why not, the cost excess
  // When not fit to load: the binding constraints by link, the likely cause
  // and the fix, naming option fields (plausibility.com_in_geometry, …).
  std::string cause;

  bool fit_to_load() const { return status == ModelVerdict::kFitToLoad; }
};

// The verdict of a plausible fit against a tolerance: converged when the
// solver says so or its point is feasible and its relative duality gap is at
// most kCertifiedGap (its cost certified within 10⁻⁶ of the optimum).
inline constexpr double kCertifiedGap = 1e-6;
IdentificationVerdict JudgePlausibleFit(const PhysicallyConsistentFit& fit, double cost_tolerance);

// How well base parameters predict a log's torques.
struct TorquePrediction {
  Eigen::VectorXd joint_rms;       // RMS of τ̂ − τ per joint [N m]
  double relative_error = 0.0;     // ‖τ̂ − τ‖ / ‖τ‖ over all joints and samples
};
struct JointTorqueIdentification {
  BaseParameters base;
  std::vector<std::string> standard_names;
  Eigen::VectorXd beta_model;   // the robot file's parameters as base parameters (C·π_model)
  // OLS, or WLS, TLS, IRLS when asked (pc: OLS). When the log does not determine every base
  // parameter, β is the minimum-norm solution, with those flagged (LinearFit);
  // the physically consistent fit keeps the robot file's values there (its prior).
  LinearFit linear;
  // Always computed: standard parameters need it (a URDF holds physical links).
  PhysicallyConsistentFit consistent;
  IdentificationVerdict verdict;  // of `consistent`: is it a robot model to load
  Eigen::VectorXd beta;         // the chosen estimator's base parameters
  TorquePrediction fit;         // β on the identification log
  TorquePrediction model_fit;   // β_model (the robot file) on the same log
};

// Base regressor stacked over a log (rows interleaved: sample·n_dof + joint).
// The log must carry qd and qdd. Throws std::invalid_argument on a size mismatch.
Eigen::MatrixXd StackBaseRegressor(const RobotModel& model, const FrictionModel& friction,
                                   const BaseParameters& base, const JointLog& log);

// The base regressor and torques of a log compressed per joint as they are
// stacked (TSQR, linear_estimator.h), without keeping W: what SolveOls and
// SolveWls need, in O(n_base²) memory. Joint j's factor covers the base
// columns that can be non-zero in its rows (links at or after j, its own
// friction terms). The samples are split into fixed parts of
// kSamplesPerFactorPart, each factored from zero on one of up to n_threads
// threads (0: the hardware's), and the parts are merged in order, so the
// result does not depend on the thread count or the scheduling. No parallel
// filtering (use StackEquations). Throws std::invalid_argument as
// StackBaseRegressor.
inline constexpr int kSamplesPerFactorPart = 2048;
StackedFactors FactorStackedEquations(const RobotModel& model, const FrictionModel& friction,
                                      const BaseParameters& base, const JointLog& log, int n_threads = 0);

// Base columns that can be non-zero in joint j's rows (per joint, ascending):
// the inertial parameters of link j and its descendants (the joints a link's
// wrench passes are its ancestors) and joint j's own friction terms; the
// column sets of the factors FactorStackedEquations returns.
std::vector<std::vector<int>> JointFactorColumns(const RobotModel& model, const FrictionModel& friction,
                                                 const BaseParameters& base);

// Torques stacked the same way.
Eigen::VectorXd StackTorques(const JointLog& log);

// W and τ of a log, parallel-filtered when `filter` is given. The rows kept
// are whole samples, still interleaved by joint.
void StackEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                    const JointLog& log, const std::optional<ParallelFilter>& filter, Eigen::MatrixXd* W,
                    Eigen::VectorXd* tau);

// The samples of the log whose rows StackEquations keeps, in order: every
// sample, or with `filter` those left after its trimming and decimation
// (ParallelFilterKeptSamples). Row block k (rows k·n_dof … k·n_dof + n_dof − 1)
// of W and τ belongs to sample kept[k]. Throws as ParallelFilterKeptSamples.
std::vector<Eigen::Index> StackedSamples(const JointLog& log, const std::optional<ParallelFilter>& filter);

// Identifies the base parameters from the log; also fits the physically
// consistent standard parameters (from the linear estimate, with the model's
// parameters as the prior for the unidentifiable directions). σ as
// options.covariance says (batch means: a second pass over W, held whole). Throws std::invalid_argument
// when the log does not fit the robot, lacks qd/qdd, or has fewer equations
// than base parameters + 1.
JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const JointLog& log,
                                              const JointTorqueOptions& options);

// The same from the log's folded equations for `base` (FactorStackedEquations,
// StreamedJointEquations: a streamed log); options.parallel_filter is not
// used (the factors are filtered or not), nor options.covariance: σ is the
// white-residual one until ApplyScoreCovariance replaces it. Throws std::invalid_argument for
// factors of another size or too few equations.
// Estimator irls needs passes over the equations: `reweighted_fold` (an
// IRLS pass over the same equations, reweighted_least_squares.h); without it,
// irls throws std::invalid_argument.
JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const BaseParameters& base,
                                              const StackedFactors& factors, const JointTorqueOptions& options,
                                              const ReweightedFold* reweighted_fold = nullptr);

// The physically consistent estimate centred on another estimate β_c of the
// same equations (e.g. a closed-loop estimator's, which least squares does not
// give): id->consistent and id->verdict replaced by the fit of
//   ‖R (β − β_c)‖² + ρ_c²,   ρ_c² = ‖W β_c − τ‖²,
// R the equations' triangular factor: the consistent model nearest to β_c in
// the data's own metric, its cost judged against β_c's (ols_cost = ρ_c²)
// instead of against least squares'. Throws as IdentifyJointTorque.
void CentreConsistentFit(const RobotModel& model, const StackedFactors& factors, const JointTorqueOptions& options,
                         const Eigen::VectorXd& beta_centre, JointTorqueIdentification* id);

// How well base parameters β predict a log's torques.
TorquePrediction PredictTorques(const RobotModel& model, const JointTorqueOptions& options,
                                const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log);

// The same from the log's folded equations. Throws std::invalid_argument
// unless β has factors.n_parameters entries.
TorquePrediction PredictTorques(const StackedFactors& factors, const Eigen::VectorXd& beta);

// Measured and predicted torques of a log over time, on the equations
// PredictTorques scores: W and τ of StackEquations (with
// options.parallel_filter, both filtered, the ends trimmed, decimated) and
// τ̂ = W β, one row per kept sample (StackedSamples), so that RMS(τ̂ − τ) per
// joint is PredictTorques' joint_rms. Holds W of the whole log while it runs
// (n_samples·n_dof × n_base). Throws std::invalid_argument as StackEquations,
// or when beta does not have base.n_base() entries.
struct TorqueSeries {
  Eigen::VectorXd t;          // [s] time of each kept sample (n_kept)
  Eigen::MatrixXd measured;   // τ [N m] (n_kept × n_dof); parallel-filtered with the log
  Eigen::MatrixXd predicted;  // τ̂ = W β [N m] (n_kept × n_dof)
};
TorqueSeries PredictTorqueSeries(const RobotModel& model, const JointTorqueOptions& options,
                                 const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log);

}  // namespace idbench
