// The excitation design as a finite-dimensional problem in the unknowns θ,
// per joint j the block [q0_j, a_j1..a_jH, b_j1..b_jH] of a Fourier series
// (fourier_series.h): the criterion with its exact gradient, the kinematic
// limits as linear rows (q, qd and qdd are linear in θ) at 25 instants per
// period of the highest harmonic (a subset of the samples when they suffice),
// torque limits, start points and box bounds. The optimizer
// (excitation_design.h) drives it; tests and benchmarks use it directly.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/link_clearance.h"
#include "idbench/engine/robot_model.h"
#include "idbench/excitation/actuator_limits.h"
#include "idbench/excitation/design_criterion.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/excitation/fourier_series.h"

namespace idbench {

struct DesignOptions;

// One linear constraint on the blocks of consecutive joints from `joint` on:
// coefficients · [block_joint, block_joint+1, …] ≤ rhs, normalised so that 1
// is the whole limit (velocity limit, joint range, …). A joint's limit spans
// its own block; a motor's velocity limit (θ̇m = A·q̇) the joints it drives.
struct LinearRow {
  int joint = 0;                 // the first joint of the span
  Eigen::VectorXd coefficients;  // (2H + 1) per joint of the span
  double rhs = 0.0;
  int group = 0;                 // 4 joint + (0 q_max, 1 qd, 2 qdd, 3 q_min), or 4 n_dof + motor for a
                                 // motor's velocity: rows of one limit
  int span(int block) const { return static_cast<int>(coefficients.size()) / block; }
};

// One torque limit, |weights · τ| ≤ limit over the grid, τ the joint torque:
// a joint's (weights = e_j) or a motor's (weights = row k of A⁻ᵀ, τm = A⁻ᵀ·τ).
struct TorqueLimit {
  Eigen::VectorXd weights;  // (n_dof)
  double limit = 0.0;       // [N m]
  std::string name;         // "torque limit of joint 'x'", "torque limit of motor 6 (joints a, b)"
};

class DesignProblem {
 public:
  // Per-thread evaluation state.
  struct Workspace {
    explicit Workspace(const DesignProblem& problem);
    DesignRegressor::Workspace regressor;
    Eigen::MatrixXd W, G, torque_rows;
    std::vector<Clearance> clearances;
    std::vector<FourierBasis> clearance_extra;  // instants added by AddClearanceInstant
    std::vector<double> clearance_extra_t;      // [s] their times
    // Per pair: the closest time found between the grid's instants, if any.
    std::vector<char> clearance_refined;
    std::vector<FourierBasis> clearance_refined_basis;
    std::vector<KinematicsData<double>> clearance_refined_pose;  // and a last one to try the next in
    std::vector<KinematicsData<double>> clearance_poses;  // per clearance instant
    std::vector<double> clearance_bounds;                 // per instant, per pair: a lower bound of the distance
    // What the last evaluation knew (per instant, per pair: a lower bound of
    // the distance, exact where GJK ran) and the joint positions it held at.
    std::vector<double> clearance_known;
    Eigen::MatrixXd clearance_known_q;
    std::vector<size_t> clearance_order, clearance_done;
    Eigen::MatrixXd clearance_q;  // n_dof × instants
    std::vector<double> clearance_done_distance;
    Eigen::VectorXd gx;
    std::vector<JointState> x;
  };

  // Keeps references to regressor; options must be valid (DesignOptions::IsValid).
  DesignProblem(const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
                const DesignOptions& options);

  int n_dof() const { return n_; }
  int harmonics() const { return H_; }
  int block() const { return block_; }  // unknowns per joint, 2H + 1
  int n_unknowns() const { return n_ * block_; }
  int n_groups() const { return 4 * n_ + (has_motor_rows_ ? n_ : 0); }
  int n_torque_constraints() const;
  // Torque limits, then one clearance constraint per pair of the clearance model.
  int n_nonlinear_constraints() const;
  const ClearanceModel* clearance() const { return clearance_ ? &*clearance_ : nullptr; }
  const std::vector<double>& times() const { return times_; }
  // The instants of the linear limit rows (rows(): per joint, per instant, 6
  // rows; then per motor with a velocity limit, per instant, 2).
  const std::vector<double>& row_times() const { return row_times_; }
  const std::vector<LinearRow>& rows() const { return rows_; }
  const DesignRegressor& regressor() const { return regressor_; }

  FourierSeriesTrajectory Trajectory(const Eigen::VectorXd& theta) const;

  // The criterion at θ and, if grad (n_unknowns), its exact gradient. A
  // rank-deficient W gives kRankDeficientValue and a zero gradient.
  static constexpr double kRankDeficientValue = 1e3;
  double Criterion(const double* theta, double* grad, Workspace* ws) const;

  // A linear row's value at θ (≤ 0 is feasible) and the worst of all rows.
  double LinearValue(const LinearRow& row, const double* theta) const;
  double MaxLinearViolation(const double* theta) const;

  // The nonlinear constraints, ≤ 0 when met; if grad (n_nonlinear_constraints
  // × n_unknowns, row-major), their gradients at the worst sample:
  //  - per joint, then per motor, with a torque limit (TorqueLimit), max over
  //    the grid of |w·τ|/τ_max − (1 − margin);
  //  - per clearance pair, max over the grid (every ⌈samples/100⌉-th sample,
  //    and the instants added) of (minimum + slack − distance)/0.1 m, the
  //    slack 1 mm, or less when the pair is closer at the home pose. A pair
  //    whose certified lower bound stays 2 cm above that at every instant is
  //    inactive: its value and gradient are the distance's at the instant of
  //    that least bound (below the exact value; both < −0.2). The bound
  //    carries what this workspace's last evaluation measured, so which
  //    pairs count as inactive depends on the evaluations before
  //    (deterministically); the other pairs' values are exact.
  void NonlinearConstraints(const double* theta, double* result, double* grad, Workspace* ws) const;
  // Nonlinear constraint i: "clearance 'a–b' >= 0.01 m", "torque limit of
  // joint 'x'"; with by how much its normalised value c > 0 breaks it:
  // "clearance 'a–b' >= 0.01 m by 0.003 m".
  std::string NonlinearConstraintName(int i) const;
  std::string DescribeViolation(int i, double c) const;

  // Adds an instant t [s] to the clearance grid of this workspace (where a
  // finer check found the links closer than the grid did).
  void AddClearanceInstant(double t, Workspace* ws) const;

  // The pose the starts oscillate about [rad] (n_dof): options.home if
  // given, else the middle of the joint ranges until set_home.
  const Eigen::VectorXd& home() const { return home_; }
  // Also sets each clearance pair's slack (see NonlinearConstraints) to what
  // it has at q: the home pose is feasible on the grid when it meets the minima.
  void set_home(const Eigen::VectorXd& q);

  // A seeded random series about the home pose, each joint scaled to 90 % of
  // its tightest kinematic limit, then the whole motion scaled down (by
  // bisection, to 1/1024 at least) until the torque and clearance constraints
  // hold on the grid: feasible on the grid when the home pose has room. A
  // joint whose motion alone breaks them at 1/1024 of its amplitude starts
  // still (zero coefficients).
  // held_still (optional) gets a line per joint started still, with the
  // constraint its motion breaks.
  Eigen::VectorXd StartPoint(unsigned seed, Workspace* ws, std::vector<std::string>* held_still = nullptr) const;
  // Box bounds: q0 inside the joint range, coefficients within twice the
  // velocity limit (a harmonic's velocity amplitude is √(a² + b²)).
  void Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const;

 private:
  void States(const double* theta, Workspace* ws) const;
  // ∂(state derivative gx of sample k) → ∂θ, accumulated into g.
  void ChainToUnknowns(const FourierBasis& basis, const Eigen::VectorXd& gx, double* g) const;
  JointState StateAt(const FourierBasis& basis, const double* theta) const;
  void BuildLinearRows();
  void ClearanceConstraints(const double* theta, double* result, double* grad, Workspace* ws) const;
  // Pair i's distance about its closest grid instant at time t: *distance and
  // *witness lowered where a time between the instants is closer.
  void RefineClearanceMinimum(const double* theta, int i, double t, double* distance, Clearance* witness,
                              Workspace* ws) const;

  const DesignRegressor& regressor_;
  std::vector<JointLimits> limits_;
  ActuatorLimits actuators_;
  std::vector<TorqueLimit> torque_limits_;
  bool has_motor_rows_ = false;
  Eigen::VectorXd home_;
  DesignCriterion criterion_;
  GivenInformation given_;  // options.given
  double f0_, duration_, margin_;
  bool rest_to_rest_;
  std::vector<double> times_;
  std::vector<FourierBasis> bases_;
  std::vector<LinearRow> rows_;
  int n_ = 0, H_ = 0, block_ = 0;
  std::optional<DesignRegressor> torque_regressor_;  // model with all joint dynamics, when τ is limited
  std::optional<ClearanceModel> clearance_;          // when the options ask for clearance and links have shapes
  int clearance_stride_ = 1;
  std::vector<double> clearance_slack_;  // [m] per pair: min(1 mm, distance at the home pose − minimum)
  std::vector<double> row_times_;  // [s]: the instants of the linear limit rows
};

}  // namespace idbench
