// Joint-torque regressor: τ = Y(q, qd, qdd) · π, linear in the standard
// parameters π of every link and the per-joint friction parameters.
//
// Per link, 10 inertial parameters about the link frame origin Bo, in B axes,
// in one order (Pinocchio's):
//   [m, m·c_x, m·c_y, m·c_z, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]
// where c = p_BoBcm_B and I = I_Bcm + m (cᵀc 𝟙 − c cᵀ) is the inertia about Bo.
// Then, per joint j and in this order for all joints, the enabled friction
// terms: Fv (viscous, τ += Fv·qd), Fc (Coulomb, τ += Fc·sign(qd), or
// tanh(qd/v) with a smoothing velocity v > 0; 0 where |qd| < a minimum speed
// when one is set), offset (τ += τ0), Ia (rotor inertia, τ += Ia·qdd).
//
// Actuator side (FrictionModel::actuator_from_joint set, transmission.h):
// the same terms act per motor k on its θ̇m_k = A_k·q̇ (A_k row k of A) and
// enter the joint torques through Aᵀ: τ += A_kᵀ (Fv_k·θ̇m_k + Fc_k·sign(θ̇m_k)
// + τ0_k + Ia_k·θ̈m_k). Then the terms are named per motor: "Fvm1", "Fcm1",
// "offsetm1", "Iam1".
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/transmission.h"

namespace idbench {

inline constexpr int kInertialParametersPerLink = 10;

struct FrictionModel {
  bool viscous = false;               // Fv per joint [N m s/rad]
  bool coulomb = false;               // Fc per joint [N m]
  bool offset = false;                // τ0 per joint [N m]
  bool rotor_inertia = false;         // Ia per joint [kg m²]
  double coulomb_smoothing = 0.0;     // v [rad/s]; 0 = sign(qd) (θ̇m on the actuator side)
  // [rad/s]; 0 = off. A sample's Coulomb column is 0 where |qd| (|θ̇m| on the
  // actuator side) is below it: near rest, where stiction and stick-slip act
  // and noise flips sign(qd), the sample still holds its inertial, viscous,
  // offset and rotor terms but says nothing of Fc. With coulomb_smoothing,
  // tanh(qd/v) above the speed, 0 below it. FloBaRoID's
  // frictionVelocityDeadZone drops such samples from its per-joint friction
  // fit; zeroing the one column keeps every equation of the fold.
  double coulomb_min_speed = 0.0;
  // A (n_dof × n_dof, transmission.h): the terms act on the actuators, per
  // motor; empty: on the joints.
  Eigen::MatrixXd actuator_from_joint{};

  bool actuator_side() const { return actuator_from_joint.size() > 0; }

  int per_joint() const { return int(viscous) + int(coulomb) + int(offset) + int(rotor_inertia); }

  // coulomb_smoothing and coulomb_min_speed each >= 0 rad/s and finite; names
  // the field in *why.
  bool IsValid(std::string* why) const;
};

// Actuator side: the motor that drives joint j alone and its ratio
// (Transmission::SingleMotorOf); nullopt for a coupled joint, or on the joint side.
std::optional<Transmission::SingleMotor> SingleMotorOf(const FrictionModel& friction, int j);

// Friction terms by name: any of "viscous", "coulomb", "offset", "rotor", or
// just "none". Returns nullopt and names the bad term in *why.
std::optional<FrictionModel> ParseFrictionTerms(const std::vector<std::string>& terms, std::string* why);

// Number of standard parameters: 10 per link plus the friction terms.
int NumStandardParameters(const RobotModel& model, const FrictionModel& friction);

// Names in π order: "B1.m", "B1.mcx", …, "B1.Izz", then "Fv1", "Fc1", … (by joint).
std::vector<std::string> StandardParameterNames(const RobotModel& model, const FrictionModel& friction);

// The model's standard parameters: inertial ones, then the enabled friction
// terms from each link's JointDynamics (offsets are zero).
Eigen::VectorXd StandardParameters(const RobotModel& model, const FrictionModel& friction);

// The model with its links' inertias and joint dynamics replaced by standard
// parameters π (layout as above; absent friction terms keep the model's
// values, offsets are dropped). Actuator side: a joint driven by one motor
// (Transmission::SingleMotorOf) gets the joint-side equivalents Ia·N²,
// Fv·N², Fc·|N|; a coupled joint's terms cannot be held per joint and are
// zero (the actuator-side values are the model). Throws std::invalid_argument (from
// RobotModel) naming a link whose parameters are not a physical body.
RobotModel ModelWithStandardParameters(const RobotModel& model, const FrictionModel& friction,
                                       const Eigen::VectorXd& pi);

// Writes Y (n_dof × NumStandardParameters) at (q, qd, qdd); data is workspace.
void ComputeJointTorqueRegressor(const RobotModel& model, const FrictionModel& friction,
                                 const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                 const Eigen::VectorXd& qdd, RobotData* data, Eigen::MatrixXd* Y);

// τ = Y(q, q̇, q̈) π for standard parameters π (any values), without
// forming Y: each link's wrench from its 10 parameters, carried to the
// joints on its path (as the regressor's blocks), plus the friction terms.
// data is workspace (left at ComputeKinematics of (q, q̇, q̈)).
void ComputeJointTorqueOfParameters(const RobotModel& model, const FrictionModel& friction,
                                    const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                    const Eigen::VectorXd& pi, RobotData* data, Eigen::VectorXd* tau);

// M(q) of standard parameters π (any values: a base-parameter estimate
// spread over π need not be a mechanism): the coefficients of q̈ in
// Y(q, q̇, q̈) π, i.e. M e_k = Y(q, 0, e_k) π − Y(q, 0, 0) π, formed without
// the regressor. A unit q̈_k gives link i (k on its path to the root) the
// body-axis ω̇ = u_ik and a_Bo = v_ik (JointArms below), so with π_i = (m, h, I)
//   M_jk = Σ_i u_ijᵀ I u_ik + m v_ijᵀ v_ik + hᵀ (v_ij × u_ik − u_ij × v_ik),
// plus the drive inertias (rotor). data holds the poses of ComputeKinematics
// at q (any q̇, q̈); M is resized to n_dof × n_dof.
void ComputeJointSpaceInertia(const RobotModel& model, const FrictionModel& friction,
                              const Eigen::VectorXd& pi, const KinematicsData<double>& data, Eigen::MatrixXd* M);

// The same on any scalar (instantiated for double and Adjoint, whose
// derivatives give ∂Y/∂(q, qd, qdd) exactly; Coulomb's sign has derivative 0).
template <typename Scalar>
void ComputeJointTorqueRegressorT(const RobotModel& model, const FrictionModel& friction,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd,
                                  KinematicsData<Scalar>* data,
                                  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>* Y);

// ⟨G, Y(q, qd, qdd)⟩ = Σ G ∘ Y for a G of Y's size, without forming Y: the
// G-weighted moment arms are gathered per link, then contracted once with the
// link's wrench terms. On Adjoint (adjoint.h) one backward sweep gives
// ∂⟨G, Y⟩/∂(q, qd, qdd), what the excitation design's gradient needs
// (instantiated for double and Adjoint).
template <typename Scalar>
Scalar ContractJointTorqueRegressorT(const RobotModel& model, const FrictionModel& friction,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd,
                                     const Eigen::Ref<const Eigen::MatrixXd>& G, KinematicsData<Scalar>* data);

}  // namespace idbench
