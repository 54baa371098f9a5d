// Drive gains (torque per motor current) of every joint from two logs of the
// same robot: one unloaded, one with a payload of known mass fixed to the
// last link (centre of mass and inertia unknown), both logs solved at once:
//
//   unloaded:  W_u β                 − diag(i_u) K = 0
//   loaded:    W_l β + Y_l φ'         − diag(i_l) K = −M · y_l
//
// with W the base regressor (joint_torque_identifier.h) and β the robot's base
// parameters (friction and rotor inertia included), the same in both logs;
// Y_l the loaded log's regressor columns of the last link's standard
// parameters [mcx, mcy, mcz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz] (about the last
// link's frame origin, in its frame) and φ' the payload's values of those;
// y_l the column of the last link's mass, M the known payload mass [kg];
// i the motor currents [A], K the drive gains [N m/A], so τ = K·i per joint.
// The known mass fixes the scale that the unloaded log alone leaves free
// (β and K can both be scaled); the payload's other parameters only take part
// in the loaded log.
// The linear least-squares solution of these equations is the start: noise
// in the currents sits in the K columns and shrinks K (errors in variables),
// so the estimate is then refined by Gauss–Newton on the same model in
// current units, e = (W β + Y φ' + M y)/K_j − i_j, where the noise is.
// References: M. Gautier, S. Briot, "Global identification of joint drive
// gains and dynamic parameters of robots", ASME J. Dyn. Syst. Meas. Control
// 136(5), 2014 (unloaded and loaded experiments with a known payload mass);
// Gautier & Khalil (σ from the residual).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "idbench/engine/enum_names.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"

namespace idbench {

struct DriveGainOptions {
  FrictionModel friction{.viscous = true, .coulomb = true};
  BaseParameterOptions base;
  double payload_mass = 0.0;  // known mass fixed to the last link [kg]

  static constexpr double kMaxPayloadMass = 1e4;  // [kg]
  // The checks that the data carry the gains (DriveGainStatus::kNotObserved):
  // the payload's torque at least this many times the loaded log's residual,
  // and the unloaded torques K·i within this factor of the robot file's.
  static constexpr double kMinPayloadSignalToNoise = 1.0;
  static constexpr double kMaxTorqueScale = 10.0;
  bool IsValid(std::string* why) const;
};

// One experiment: the motion and the motor currents.
struct CurrentLog {
  JointLog motion;          // t, q, qd, qdd (tau unused)
  Eigen::MatrixXd current;  // motor currents [A] (n_samples × n_dof)
  // Set when qd, qdd were estimated by that filter: the equations' columns
  // (regressor and currents) are then filtered in parallel.
  std::optional<ParallelFilter> parallel_filter;
};

enum class DriveGainStatus {
  kEstimated,         // every gain is determined by the logs
  kNotIdentifiable,   // some gain is not (message names which and why)
  kNotObserved,       // determined in rank, but the data do not carry them: the payload not seen above the
                      // noise, or torques K·i against or far from the robot file's (message says what to check)
};

inline constexpr EnumNames<DriveGainStatus, 3> kDriveGainStatusNames{"status",
                                                                   {"estimated", "not identifiable", "not observed"}};

struct DriveGainEstimate {
  DriveGainStatus status = DriveGainStatus::kEstimated;
  std::string message;          // what is not identifiable, and what to change
  Eigen::VectorXd gains;        // K [N m/A] (n_dof); NaN where not identifiable
  // Standard deviation of K [N m/A] (n_dof); ∞ where not identifiable: from
  // the residual as it is (batch means, residual_covariance.h), and as if it
  // were white.
  Eigen::VectorXd sigma, sigma_white;
  CovarianceSummary covariance_method;  // how `sigma` was computed
  BaseParameters base;          // the robot's base parameters β stands for
  Eigen::VectorXd beta;         // β (n_base); NaN where not identifiable
  Eigen::VectorXd payload;      // φ' [kg m, kg m²] (9); NaN where not identifiable
  std::vector<std::string> unknown_names;  // β names, payload names, K1..Kn
  std::vector<bool> identifiable;          // per unknown
  int rank = 0;                 // of the stacked equations (column-normalised)
  Eigen::Index n_equations = 0;
  // Residual RMS of each log's equations (W β − K·i) [N m], per joint (n_dof).
  Eigen::VectorXd unloaded_rms, loaded_rms;
  // ‖residual‖ / ‖K·i‖ over each log.
  double unloaded_relative_error = 0.0, loaded_relative_error = 0.0;
  // The unloaded log's torques K·i against the robot file's prediction
  // W β_file: ⟨K·i, W β_file⟩ / ‖W β_file‖² (≈ 1 for right gains and a fair
  // robot file; ≤ 0 when the logs are swapped).
  double torque_scale = 0.0;
  // ‖payload torque in the loaded log‖ / ‖that log's residual‖ (∞ without noise).
  double payload_signal_to_noise = 0.0;
};

// The payload's parameter names, in φ' order: "mcx", …, "Izz".
const std::vector<std::string>& PayloadParameterNames();

// Estimates the drive gains. Both logs must carry qd, qdd and currents of the
// robot's joints. Then checks that the data carry them (kNotObserved): the
// payload's torque stands out of the loaded log's residual, and the unloaded
// torques K·i are of the sign and size the robot file predicts (swapped
// logs turn every gain negative). σ² = ‖e‖²/(m − rank) times the diagonal of (JᵀJ)⁺ (J the
// Jacobian of the current residual e), the identifiable directions only. Gains that the logs do not
// determine (a joint whose payload torque is not excited: the loaded motion
// must move the payload so that its mass shows at every joint) give status
// kNotIdentifiable with a message, not a throw. Throws std::invalid_argument
// for invalid options, logs that do not fit the robot, or fewer equations than
// unknowns + 1.
DriveGainEstimate EstimateDriveGains(const RobotModel& model, const CurrentLog& unloaded, const CurrentLog& loaded,
                                     const DriveGainOptions& options);

}  // namespace idbench
