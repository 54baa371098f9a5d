// Recursive Newton–Euler inverse dynamics, with the wrench through every hinge.
#pragma once

#include "idbench/engine/kinematics.h"

namespace idbench {

// Runs ComputeKinematics, then the backward Newton–Euler pass. For every link
// B with parent P it writes the force f_PB_W and the moment m_PB_Bo_W (about
// the hinge point) that the hinge transmits from P onto B, so that for link B
// with children C:
//   m (a_WBcm - g) = f_PB - Σ_C f_BC,
//   I ẇ + ω × I ω  = m_PB - Σ_C (m_BC + (p_Co - p_Bo) × f_BC) - (p_Bcm - p_Bo) × m (a - g) (about Bo).
// tau_i = axis_i · m_PB_Bo_W[i]. Returns data->tau.
const Eigen::VectorXd& InverseDynamics(const RobotModel& model, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                       RobotData* data);

// Adds the joint-side drive and friction torques of the model's JointDynamics:
//   τ_j += Fv_j qd_j + Fc_j sign(qd_j) + Ia_j qdd_j   [N m].
// The rigid-body torque (InverseDynamics) plus these is what a motor supplies.
void AddJointDynamicsTorque(const RobotModel& model, const Eigen::VectorXd& qd,
                            const Eigen::VectorXd& qdd, Eigen::VectorXd* tau);

}  // namespace idbench
