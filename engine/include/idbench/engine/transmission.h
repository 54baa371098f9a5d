// A transmission from actuators (motors) to joints: gear ratios and
// couplings, e.g. a wrist where one motor turns with another joint.
//
// With A = actuator_from_joint (n_dof × n_dof, invertible) and the joint
// offset q0 (n_dof):
//   θ̇m = A·q̇                 actuator velocities [rad/s]
//   q  = A⁻¹·θm + q0          joint positions [rad]
//   τ  = Aᵀ·τm                joint torques [N m] from actuator torques,
// the last by virtual work (τᵀq̇ = τmᵀθ̇m). A diagonal A holds the reductions
// N_j (θm_j = N_j·q_j). The Stäubli TX40's wrist, where motor 6 turns with
// joint 5 (q6 = θm6/N6 − q5), has A(6, 5) = A(6, 6) = N6.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace idbench {

struct Transmission {
  Eigen::MatrixXd actuator_from_joint;  // A (n_dof × n_dof) [rad of motor per rad of joint]
  Eigen::VectorXd joint_offset;         // q0 [rad] (n_dof); empty: zero
  std::string source;                   // where it was given, for notes ("log.json: .transmission")

  // A = diag(reduction).
  static Transmission FromReduction(const std::vector<double>& reduction);

  int n_dof() const { return static_cast<int>(actuator_from_joint.rows()); }
  // Beyond any robot drive: a motor turning more than kMaxRatio rad per rad
  // of a joint, or a joint turning more than kMaxRatio rad per rad of the
  // motors (as drive gains are bounded, JointLogFormat). Within it the
  // actuator-side regressor columns (∝ N, N²) stay within 1e8 of the
  // joint-side ones, which the base parameters and the estimators resolve.
  static constexpr double kMaxRatio = 1e4;

  // A square, n_dof × n_dof, finite and invertible (smallest singular
  // value above 1e-12 of the largest), every entry within ±kMaxRatio and the
  // smallest singular value at least 1/kMaxRatio, joint_offset empty or n_dof
  // finite values. *why names the field ("actuator_from_joint: expected 6 × 6,
  // got 6 × 5", "actuator_from_joint[2][2]: ...").
  bool IsValid(int n_dof, std::string* why) const;

  // Rows are samples, columns actuators or joints (as JointLog's matrices).
  // q = A⁻¹·θm + q0 per row.
  Eigen::MatrixXd JointPositions(const Eigen::MatrixXd& theta_m) const;
  // q̇ = A⁻¹·θ̇m per row (also accelerations).
  Eigen::MatrixXd JointRates(const Eigen::MatrixXd& thetad_m) const;
  // τ = Aᵀ·τm per row.
  Eigen::MatrixXd JointTorques(const Eigen::MatrixXd& tau_m) const;

  // The one motor that drives joint j alone, and its ratio N = A(k, j): the
  // only non-zero of column j is in row k, and it is row k's only non-zero.
  // nullopt for a coupled joint.
  struct SingleMotor {
    int motor;
    double ratio;
  };
  std::optional<SingleMotor> SingleMotorOf(int j) const;
};

}  // namespace idbench
