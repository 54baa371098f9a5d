// A payload's inertial parameters from the joint torques of a robot that
// carries it, fixed to one link B (its 10 parameters φ = [m, mcx, mcy, mcz,
// Ixx, Ixy, Iyy, Ixz, Iyz, Izz] about Bo in B axes, joint_torque_regressor.h):
// the payload adds Y_B φ to the torques, Y_B the link's 10 columns of the
// joint-torque regressor.
//
//   one log:   Y_B,l φ = τ_l − τ_model(q, qd, qdd)          (the robot's model subtracted)
//   two logs:  W_u β         = τ_u                          (unloaded)
//              W_l β + Y_B,l φ = τ_l                        (loaded)
//
// τ_model is the robot file's inverse dynamics with its joint friction and
// rotor inertia; W the base regressor and β the robot's base parameters
// (friction included), estimated from both logs at once, so that the robot
// file's inertial errors cancel (Gautier & Briot's loaded/unloaded pair, as in
// drive_gains.h). σ² = ‖e‖²/(m − rank) times (AᵀA)⁺ (Gautier & Khalil), for
// φ and, by first-order propagation, for the mass, the centre of mass
// p_BoPcm_B = h/m and the inertia about it I_Pcm_B = I_Bo − (hᵀh 𝟙 − h hᵀ)/m.
// The physically consistent estimate is the least-squares one projected, in
// the metric of its information matrix, onto the payloads whose
// pseudo-inertia is positive definite (physically_consistent.h; Wensing, Kim
// & Slotine 2017).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/ident/physically_consistent.h"

namespace idbench {

struct PayloadEstimatorOptions {
  int link = -1;  // index of the link carrying the payload; -1: the last link
  // The robot's joint terms estimated with β (two logs only; with one log the
  // robot file's friction and rotor inertia are subtracted).
  FrictionModel friction{.viscous = true, .coulomb = true, .rotor_inertia = true};
  BaseParameterOptions base;
  // The verdict's bounds (PayloadStatus): the consistent estimate within
  // this Mahalanobis distance of the least-squares one (√χ² of 10
  // parameters: 5 is about its 99.5 % quantile), and each
  // quantity's σ at most max_relative_sigma of its scale: the mass; for the
  // centre of mass max(|c|, radius of gyration); for the inertia tr(I)/2.
  double max_relative_sigma = 0.1;
  double max_projection_distance = 5.0;

  // Checks the options for `model`; *why names the field.
  bool IsValidFor(const RobotModel& model, std::string* why) const;
};

// One experiment: t, q, qd, qdd and the joint torques τ [N m].
struct TorqueLog {
  JointLog motion;
  // Set when qd, qdd were estimated by that filter: the equations' columns
  // (regressor and torques) are then filtered in parallel.
  std::optional<ParallelFilter> parallel_filter;
};

enum class PayloadStatus {
  kEstimated,         // every parameter determined, σ small against each quantity's scale, a physical body
  kNotIdentifiable,   // the motion does not determine some parameters (not_identifiable says which and why)
  kPoorlyDetermined,  // determined, but some σ above the bound against its scale
  kNotPhysical,       // the physically consistent estimate is far (in σ) from what the data say
};

// "estimated", "not identifiable", "poorly determined", "not physical".
const char* PayloadStatusName(PayloadStatus status);

// The payload as a user gives it to a controller.
struct PayloadBody {
  double mass = 0.0;             // [kg]
  Eigen::Vector3d p_BoPcm_B;     // centre of mass in the link's frame [m]
  Eigen::Matrix<double, 6, 1> I_Pcm_B;  // inertia about the centre of mass, B axes: Ixx, Ixy, Ixz, Iyy, Iyz, Izz [kg m²]
};

// Names of PayloadBody's 10 quantities in the order of PayloadQuantities:
// "mass", "com_x", "com_y", "com_z", "Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz".
const std::vector<std::string>& PayloadQuantityNames();
// Names of φ: "m", "mcx", "mcy", "mcz", "Ixx_Bo", "Ixy_Bo", "Iyy_Bo", "Ixz_Bo", "Iyz_Bo", "Izz_Bo" (inertia about the link origin).
const std::vector<std::string>& PayloadInertialParameterNames();

// The body of φ, and the 10 quantities [mass, com, inertia] as one vector.
PayloadBody PayloadBodyFromParameters(const InertialParameters& phi);
Eigen::Matrix<double, 10, 1> PayloadQuantities(const PayloadBody& body);
// ∂(quantities)/∂φ at φ (10 × 10).
Eigen::Matrix<double, 10, 10> PayloadQuantityJacobian(const InertialParameters& phi);
// The scale quantity k's σ is judged against (the verdict's
// max_relative_sigma): the mass; for the centre of mass max(|c|, radius of
// gyration √(tr I/2m)); for the inertia tr(I)/2.
double PayloadQuantityScale(const PayloadBody& body, int k);
// φ of a body (the inverse of PayloadBodyFromParameters).
InertialParameters PayloadParametersFromBody(const PayloadBody& body);

struct PayloadEstimate {
  PayloadStatus status = PayloadStatus::kEstimated;
  std::string message;             // why the status is not kEstimated, and what to change
  bool two_logs = false;
  int link = -1;                   // index of the payload's link
  // Least squares: φ and its covariance (NaN where not identifiable): from
  // the residual as it is (batch means, residual_covariance.h), and as if it
  // were white.
  InertialParameters phi;
  Eigen::Matrix<double, 10, 10> covariance;
  Eigen::Matrix<double, 10, 10> covariance_white;
  CovarianceSummary covariance_method;       // how `covariance` was computed
  std::vector<bool> parameter_identifiable;  // per φ entry (10)
  // The 10 quantities (PayloadQuantityNames): identifiable when every φ entry
  // they depend on is; the reason names the ones missing.
  std::vector<bool> identifiable;            // (10)
  std::vector<std::string> not_identifiable_reason;  // "" where identifiable (10)
  // The physically consistent estimate (all NaN unless every φ is identifiable).
  InertialParameters consistent_phi;
  PayloadBody body;                          // of consistent_phi
  Eigen::Matrix<double, 10, 1> sigma;        // σ of the 10 quantities at it; NaN where not identifiable
  Eigen::Matrix<double, 10, 1> sigma_white;  // the same from covariance_white
  double projection_distance = 0.0;          // ‖consistent − least squares‖ in σ (Mahalanobis, `covariance`)
  double min_pseudo_inertia_eigenvalue = 0.0;  // of the least-squares φ [kg m²]
  // Fit.
  int rank = 0;                    // of the stacked equations
  Eigen::Index n_equations = 0;
  double residual_rms = 0.0;       // [N m]
  double payload_signal_to_noise = 0.0;  // ‖Y_B φ‖ / ‖residual‖ over the loaded log (∞ without noise)
};

// Estimates the payload on options.link from the loaded log, and the unloaded
// one when given (same robot and, best, the same motion). Parameters the
// motion does not determine are status kNotIdentifiable with a message, not a
// throw. Throws std::invalid_argument for invalid options, logs that do not
// fit the robot, or fewer equations than unknowns + 1.
PayloadEstimate EstimatePayload(const RobotModel& model, const TorqueLog& loaded, const TorqueLog* unloaded,
                                const PayloadEstimatorOptions& options);

}  // namespace idbench
