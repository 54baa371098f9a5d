// Excitation design: the Fourier-series motion (fourier_series.h) whose
// identification regressor W (design_regressor.h) minimises a criterion
// (design_criterion.h) within the joints' position, velocity, acceleration
// and torque limits.
//
// Unknowns, per joint j: [q0_j, a_j1..a_jH, b_j1..b_jH]. q, qd and qdd are
// linear in them, so the kinematic limits on the sample grid are linear
// constraints A θ ≤ b; torque limits are nonlinear (inverse dynamics). The
// limits are tightened by `margin` during the search and the result is
// re-checked on a fine grid (check_rate_hz) against the untightened limits.
//
// Several starts (seeded; start k uses seed + k) run on `threads` threads;
// each start is deterministic, so for a given seed the design does not
// depend on the thread count or timing (unless max_seconds cuts it short).
// The best feasible point any start visited is the result.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/enum_names.h"
#include "idbench/engine/link_clearance.h"
#include "idbench/engine/cell.h"
#include "idbench/engine/robot_model.h"
#include "idbench/excitation/actuator_limits.h"
#include "idbench/excitation/design_criterion.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/excitation/fourier_series.h"
#include "idbench/excitation/ramped_trajectory.h"

namespace idbench {

enum class DesignAlgorithm { kSlsqp, kMma, kCobyla, kSbplx };
inline constexpr EnumNames<DesignAlgorithm, 4> kDesignAlgorithmNames{"algorithm", {"slsqp", "mma", "cobyla", "sbplx"}};
std::vector<std::string> DesignAlgorithmNames();  // "slsqp", "mma", "cobyla", "sbplx"
std::string DesignAlgorithmName(DesignAlgorithm algorithm);
// false with *why = "algorithm: expected slsqp, mma, cobyla or sbplx, got '...'".
bool ParseDesignAlgorithm(std::string_view text, DesignAlgorithm* algorithm, std::string* why = nullptr);

struct DesignOptions {
  int harmonics = 5;               // H
  double f0 = 0.1;                 // base frequency [Hz]
  double duration = 0.0;           // [s]; 0 means one period, 1/f0
  bool rest_to_rest = false;       // add the quintic that starts and ends at rest
  int samples = 250;               // sample times of the criterion and the constraint grid
  DesignCriterion criterion = DesignCriterion::kLogCond;
  DesignAlgorithm algorithm = DesignAlgorithm::kSlsqp;
  int starts = 4;
  unsigned seed = 1;
  int threads = 2;
  int max_evaluations = 300;       // per start
  double max_seconds = 0.0;        // whole design; 0 = no limit
  double margin = 0.02;            // limits tightened by this fraction during the search
  double clearance = 0.01;         // [m] between links that no joint connects, to the floor z = 0 and
                                   // to the scene's obstacles (link_clearance.h); negative: not checked
  Cell scene;                     // the cell in the world: floor on/off, obstacles (cell.h)
  BasePose base_pose;              // the robot's base in the world; the regressor's model must have its
                                   // gravity (MountRobot, base_pose.h)
  double check_rate_hz = 1000.0;   // re-check of the result
  Eigen::VectorXd home;            // [rad] (n_dof): the pose the starts oscillate about;
                                   // empty: FindHomePose (home_pose.h)
  double ramp_seconds = 0.0;       // [s] in [0, kMaxRampSeconds]: rest-to-rest ramps from the home
                                   // to the motion and back (ramped_trajectory.h), in the re-check
  static constexpr double kMaxRampSeconds = 600.0;
  ActuatorLimits actuators;        // motor-side velocity and torque limits through a transmission
                                   // (actuator_limits.h), kept as the joints' are; empty: none
  // The information of motions already recorded (design --given,
  // design_criterion.h): the criterion, DesignResult::initial and final are
  // then those of the union; empty: the new motion alone.
  GivenInformation given;

  double period_duration() const { return duration > 0.0 ? duration : 1.0 / f0; }
  // Checks ranges; names the bad option in *why.
  bool IsValid(std::string* why) const;
  // The clearance model of a robot in this cell (scene, base_pose), or none
  // when clearance < 0 or no link has a shape.
  std::optional<ClearanceModel> MakeClearance(const RobotModel& model) const;
};

// One checked constraint: the worst instant of one joint's limit.
struct ConstraintMargin {
  std::string quantity;  // "q_min", "q_max", "qd", "qdd", "tau", "clearance"
  int joint = 0;         // 0-based (clearance: the pair's index)
  std::string pair;      // clearance: "link4–link2", "link5–ground"
  double time = 0.0;     // [s] of the worst sample
  double value = 0.0;    // q, |qd|, |qdd| or |τ| there
  double limit = 0.0;
  double margin = 0.0;   // limit − value (for q_min: value − limit); < 0 is a violation
  bool held_at_home = false;  // clearance: limit is the pair's distance at q = 0, closer than
                              // the clearance asked (link_clearance.h)
  std::string obstacle;       // clearance to what is not a moving link: "ground" (the floor), the obstacle's
                              // or the ground link's name; "" between moving links
  ClearanceOther other = ClearanceOther::kLink;  // clearance: what `obstacle` is (the floor is told by
                                                 // this, never by its name)
  int obstacle_index = -1;    // clearance to a scene obstacle: its index in scene.obstacles
  std::string link;           // clearance: the robot's link of the pair
  int motor = -1;             // an actuator limit's motor (0-based; quantity "qd" or "tau" of θ̇m, τm); −1: a joint's
  std::string driven;         // motor: the joints it drives, "joint_5, joint_6"
};

struct FeasibilityCheck {
  double rate_hz = 0.0;
  std::vector<ConstraintMargin> margins;  // every joint × quantity with a finite limit
  bool feasible() const;
  // One line per violated constraint: "joint 2 qd: |qd| = 1.62 rad/s at t = 3.41 s
  // exceeds the limit 1.5 rad/s by 0.12 rad/s", "motor 6 (joints joint_5,
  // joint_6) qd: |θ̇m| = 210 rad/s at t = 3.41 s exceeds the limit 200 rad/s
  // by 10 rad/s"; "" if feasible.
  std::string Explain() const;
  // The clearance margin to the cell (the floor or an obstacle; not a ground
  // link of the robot) whose distance came lowest; nullptr when none was checked.
  const ConstraintMargin* ClosestObstacle() const;
  // "closest obstacle: wall, 0.0312 m from wrist_3_link at t = 2.41 s (minimum 0.01 m)"; "" when none.
  std::string ClosestObstacleLine() const;
};

// Checks a trajectory's q, qd, qdd and joint torque (inverse dynamics plus
// the model's joint dynamics) against the limits at rate_hz; when clearance
// is given, the distance of every pair against its minimum; and the motors'
// θ̇m = A·q̇ and τm = A⁻ᵀ·τ against the actuator limits (none when empty).
FeasibilityCheck CheckTrajectoryLimits(const RobotModel& model, const std::vector<JointLimits>& limits,
                                       const Trajectory& trajectory, double rate_hz,
                                       const ClearanceModel* clearance = nullptr,
                                       const ActuatorLimits& actuators = {});

// The limits of every joint must bound the motion: a finite velocity and
// acceleration limit > 0, q_min < q_max. Throws std::invalid_argument naming
// the joint and the limit otherwise.
void CheckDesignLimits(const RobotModel& model, const std::vector<JointLimits>& limits);

struct DesignProgress {
  int start = 0;             // 0-based
  int evaluations = 0;       // of this start
  double best_value = 0.0;   // best feasible criterion of this start (inf: none yet)
  bool feasible = false;
};

struct DesignControl {
  const std::atomic<bool>* stop = nullptr;                       // set (e.g. on Ctrl-C) to stop early
  std::function<void(const DesignProgress&)> progress;           // called from worker threads
};

struct DesignStartSummary {
  double initial_value = 0.0;  // criterion at the start point
  double best_value = 0.0;     // best feasible value visited (inf: none)
  int evaluations = 0;
  int feasible_at = -1;        // evaluation at which it first met every limit on the grid
                               // (0: the start point itself); −1: never
  std::string status;          // NLopt's result or "stopped"
  // Worst normalised constraint violation (≤ 0: feasible on the grid) at the
  // start point and where the search ended.
  double initial_violation = 0.0, final_violation = 0.0;
  // Whether the start got anywhere: a feasible start improved its criterion;
  // an infeasible one became feasible or reduced its violation.
  bool progressed = false;
  // "improved", "no progress: …", "infeasible: …" (one line, for the start's line and design.json).
  std::string outcome;
};

// What a design came to. Only kFeasible carries a design (a start met every
// limit on the sample grid; DesignResult::usable() says whether it also holds
// at the check rate and improved); the others explain why there is none
// (DesignResult::infeasibility).
enum class DesignStatus {
  kFeasible,
  kInfeasible,        // the search ran and no start met the limits (and the clearance) on the grid
  kNoRoom,            // before the search: the cell's obstacles leave the arm no room at its home
  kNoMotionPossible,  // before the search: the settings admit no motion whatever the surroundings
                      // (the home pose violates a limit or the clearance to the ground)
  kNotExcited,        // the search found a feasible motion, but within these limits it leaves
                      // parameters unexcited (rank of W below the parameter count)
};
inline constexpr EnumNames<DesignStatus, 5> kDesignStatusNames{
    "status", {"feasible", "infeasible", "no_room", "no_motion_possible", "not_excited"}};

// No feasible design, explained: every violated constraint (FeasibilityCheck
// form) and which settings to relax. before_search: the settings admit no
// motion at all (the home pose itself violates a limit or the clearance, or no
// pose with room was found), seen before any search ran; otherwise the search
// ran and no start met every limit, and check is the 1 kHz check of the
// least-violating point it reached. kNotExcited: the explanation names the
// rank, the parameters left unexcited and the joints held still; check is the
// design's own, advice is empty.
struct DesignInfeasibility {
  // The summary, one line per violation and the "to relax:" lines: the
  // message a front end shows (fields named as in the options, not flags).
  std::string explanation;
  FeasibilityCheck check;
  std::vector<std::string> advice;
  bool before_search = false;
};

struct DesignResult {
  DesignResult(FourierSeriesTrajectory t, FourierSeriesTrajectory start)
      : trajectory(std::move(t)), initial_trajectory(std::move(start)) {}
  DesignStatus status = DesignStatus::kFeasible;
  DesignInfeasibility infeasibility;  // when status is not kFeasible; empty otherwise
  FourierSeriesTrajectory trajectory;
  FourierSeriesTrajectory initial_trajectory;  // the winning start's first point
  double initial_value = 0.0;        // criterion of the best start's initial point (NaN: no design;
                                     // kNotExcited: the unexciting design's)
  double value = 0.0;                // criterion of the result (NaN: no design; kNotExcited: as above)
  Identifiability initial, final;    // of W on the design grid (kFeasible, kNotExcited)
  FeasibilityCheck check;            // of RobotTrajectory() at check_rate_hz (times from its start);
                                     // not kFeasible: infeasibility.check
  std::vector<DesignStartSummary> starts;
  Eigen::VectorXd home;              // [rad] (n_dof): the pose the starts oscillated about
  std::string home_source;           // "mid-range", "searched", "given"
  int evaluations = 0;               // all starts
  double wall_seconds = 0.0;
  bool stopped = false;              // stopped early by the control flag
  // Whether this is a design to run: a design (kFeasible), feasible at the
  // check rate and better than the start point it came from (the search made
  // progress); else why not, one line ("" when usable).
  bool usable() const { return Rejection().empty(); }
  std::string Rejection() const;
  double ramp_seconds = 0.0;         // [s] DesignOptions::ramp_seconds

  // What the robot runs: the trajectory framed by the ramps from and to the
  // home (the trajectory itself when ramp_seconds is 0).
  RampedTrajectory RobotTrajectory() const;
};

// The sample times of the criterion and the constraint grid.
std::vector<double> DesignSampleTimes(const DesignOptions& options);

// What to relax for each violated constraint of check: the joint's limit in
// the limits file, --clearance, --margin, --home, --harmonics/--f0/--duration,
// --ramp for a violation during a ramp (check times from the first ramp's start).
std::vector<std::string> RelaxationAdvice(const FeasibilityCheck& check, const DesignOptions& options,
                                          bool before_search);

// Throws std::invalid_argument naming --samples or --starts when what the
// design holds for them (per sample: every thread's regressor rows, the limit
// rows, the basis; per start: its coefficients) would not fit the memory
// budget of idbench/engine/resource_limits.h. DesignExcitation checks it first;
// a caller that allocates per start checks it before.
void CheckDesignFitsInMemory(const DesignRegressor& regressor, const DesignOptions& options);

// Runs the design. Throws std::invalid_argument for invalid options or
// limits (see above). When the settings admit no motion, no start reached a
// feasible point or the feasible design leaves parameters unexcited, the
// result says so (status, infeasibility); its trajectories are then the
// least-violating point the search ended at and its start, (before the
// search) the motionless home, or (kNotExcited) the unexciting design.
DesignResult DesignExcitation(const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
                              const DesignOptions& options, const DesignControl& control = {});

}  // namespace idbench
