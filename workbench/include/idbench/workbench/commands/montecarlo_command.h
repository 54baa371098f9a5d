// `idbench montecarlo`: how much to trust joint-torque identification under
// torque noise. One noise-free Bullet experiment (and a held-out one) is
// simulated; every trial adds fresh seeded noise to the torques (white, or
// coloured to a band), identifies by WLS with σ from the residual as it is
// (batch means, residual_covariance.h), and is compared with the truth: the
// spread against the printed σ, and how often the printed 95 % intervals
// hold the truth (coverage). With record_derivatives off, each trial
// identifies from t, q, τ as a robot's log: qd, qdd from the filtered q and
// the equations parallel-filtered, as identify does.
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/enum_names.h"
#include "idbench/engine/trajectory.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/logs/signal_filter.h"

namespace idbench {

// The torque noise of a simulated experiment when none is given, for a robot
// of any number of joints: σ = 0.5 N m on the first three joints (the arm's,
// which carry the load), 0.05 N m on the others (the wrist's).
std::vector<double> DefaultTorqueNoise(int n_dof);
// `tau_noise` as given (one σ for all joints, or one per joint), or
// DefaultTorqueNoise(n_dof) when empty. Throws std::invalid_argument naming
// `tau_noise` when it has neither 1 nor n_dof values.
std::vector<double> TorqueNoiseOrDefault(const std::vector<double>& tau_noise, int n_dof);

struct MonteCarloOptions {
  std::string robot = "puma560";
  std::string trajectory = "general";          // identification motion: built-in or .json/.csv file
  std::string held_out = "general-reversed";   // validation motion: built-in or file
  double duration = 10.0;                      // [s] of built-in motions; a file brings its own
  double dt = 1e-3;                            // simulation step [s]
  int samples = 1000;                          // samples over the identification motion's duration
  std::vector<double> tau_noise;               // σ per joint (or one for all) [N m]; empty: DefaultTorqueNoise
  double tau_noise_bandwidth_hz = 0.0;         // 0: white; else coloured to this band (SensorOptions)
  // true: the simulator's exact qd, qdd; false: t, q, τ only, through
  // `filter` (identify's filter path, its defaults: trims 5/fc).
  bool record_derivatives = true;
  LogFilterOptions filter{.trim_s = -1.0};
  std::vector<std::string> friction{"viscous", "coulomb", "rotor"};
  int trials = 100;
  unsigned seed = 1;
  std::string out_dir;                         // montecarlo.json when given
  std::string command_line;

  bool IsValid(std::string* why) const;
};

// What RunMonteCarlo came to: the trials ran (kCompleted), or the motion
// does not excite every base parameter (W rank-deficient), so no trial has
// an estimate (kNotExcited; message says so, and the statistics are empty).
enum class MonteCarloStatus { kCompleted, kNotExcited };
inline constexpr EnumNames<MonteCarloStatus, 2> kMonteCarloStatusNames{"status", {"completed", "not_excited"}};

struct MonteCarloReport {
  MonteCarloStatus status = MonteCarloStatus::kCompleted;
  // kNotExcited: "montecarlo: the motion does not excite every base parameter
  // (W has rank 30 of 36); choose a richer `trajectory` (see compare)"; "" otherwise.
  std::string message;
  std::string trajectory, held_out;    // the motions' names (options' trajectory and held_out)
  int trials = 0, samples = 0;         // as run
  std::vector<double> tau_noise;       // σ per joint (or one for all) [N m], as run
  double tau_noise_bandwidth_hz = 0.0; // as run (0: white)
  bool record_derivatives = true;      // as run (false: the filter path)
  JointLog log;                        // the noise-free identification log (Bullet-executed states)
  BaseParameters base;
  Eigen::VectorXd beta_true;           // C·π of the robot file (n_base)
  Eigen::VectorXd predicted_sigma;     // mean over trials of the printed σ per base parameter (batch means)
  Eigen::VectorXd predicted_sigma_white;  // the same for the white-residual formula
  Eigen::VectorXd empirical_sigma;     // standard deviation of the trials' estimates
  Eigen::VectorXd empirical_bias;      // mean estimate − truth
  double mean_relative_error = 0.0;    // mean over trials of ‖β̂ − β‖/‖β‖
  double predicted_relative_error = 0.0;  // √(tr cov)/‖β‖ from the predicted covariance
  double mean_held_out_error = 0.0;    // mean ‖τ̂ − τ‖/‖τ‖ on the noisy held-out log
  double held_out_noise_floor = 0.0;   // the same for the true parameters (noise alone)
  double worst_sigma_ratio = 0.0;      // max |empirical/predicted − 1| over base parameters
  int worst_sigma_index = 0;
  // Fraction of trials × base parameters whose printed 95 % interval
  // β̂ ± 1.96 σ holds the truth: with σ from batch means (coverage) and from
  // the white-residual formula (coverage_white). Honest σ: about 0.95.
  double coverage = 0.0, coverage_white = 0.0;
  double n_effective = 0.0;            // mean over trials of the fits' effective sample count
  int n_equation_samples = 0;          // samples whose equations each trial fits (after filtering's trim)

  // Five lines: what ran, the mean error against the predicted one, the worst
  // σ ratio, the coverage and the held-out error against the noise alone (the
  // first and last lines of FormatMonteCarloTables); kNotExcited: what ran
  // and message.
  std::string BriefReport() const;
};

// The most Monte-Carlo trials montecarlo and compare run (each costs one
// weighted least-squares fit).
constexpr int kMaxTrials = 100000;

// Throws std::invalid_argument naming `option` (--samples) when `samples`
// samples of simulated log and regressor rows (at most 6 rows of 14 parameters
// per joint: per-body or torque with friction) would not fit the memory budget
// (idbench/engine/resource_limits.h).
void CheckRegressorSamples(const std::string& option, double samples, int n_dof);

// Throws std::invalid_argument naming a bad option or motion file; a motion
// that does not excite every base parameter is the report's status.
MonteCarloReport RunMonteCarlo(const RobotModel& model, const MonteCarloOptions& options);
// The same along `motion` (options.trajectory then only names it).
MonteCarloReport RunMonteCarlo(const RobotModel& model, const MonteCarloOptions& options, const Trajectory& motion);
// The tables and montecarlo.json of a report with status kCompleted
// (std::logic_error otherwise: there are no statistics to format).
std::string FormatMonteCarloTables(const MonteCarloOptions& options, const MonteCarloReport& report);
std::string FormatMonteCarloJson(const MonteCarloOptions& options, const MonteCarloReport& report);

}  // namespace idbench
