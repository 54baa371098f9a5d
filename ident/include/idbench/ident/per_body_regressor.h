// The seed paper's per-body equations (paper-method.md), linear in the mass
// and the principal moments of inertia of one body B:
//   Newton (world axes):  m (a_WBcm − g) = f_PB − Σ_C f_BC                 (eq. 17)
//   Euler (body axes, about Bcm):  S(Λ, Λ', Λ'') [J11 J22 J33]ᵀ = N_B       (eq. 18)
// with S_kl = δ_kl ω̇_k + (ω×)_kl ω_l, ω = 2 L(Λ) Λ', ω̇ = 2 L(Λ) Λ'', and N_B
// the moment about Bcm of every hinge wrench acting on B.
// Assumes the link frame axes are principal axes of the body (as in paper6r).
#pragma once

#include <Eigen/Core>
#include <string>

#include "idbench/engine/quaternion.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/measurements.h"

namespace idbench {

// Euler regressor in the paper's quaternion form (eqs. 7, 18), written in the
// λ's without forming ω: J ω̇ + ω × J ω = 2 L(Λ)Λ'' ∘ J + 4 L(Λ) L(Λ')ᵀ J L(Λ) Λ', so
//   S = 2 diag(L Λ'') + 4 L L'ᵀ diag(L Λ').
Eigen::Matrix3d EulerRegressorQuaternion(const QuaternionRates& rates);
// The same from body-frame ω, ω̇ (eq. 5): S = diag(ω̇) + [ω]× diag(ω).
// Any scalar (double, or Adjoint for derivatives).
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> EulerRegressorOmega(const Eigen::Matrix<Scalar, 3, 1>& w_B,
                                                const Eigen::Matrix<Scalar, 3, 1>& wd_B) {
  const Scalar z(0.0);
  Eigen::Matrix<Scalar, 3, 3> w_cross;
  w_cross << z, -w_B.z(), w_B.y(),  //
      w_B.z(), z, -w_B.x(),         //
      -w_B.y(), w_B.x(), z;
  return Eigen::Matrix<Scalar, 3, 3>(wd_B.asDiagonal()) + w_cross * w_B.asDiagonal();
}

// Rows of one body at one log step.
struct PerBodyRows {
  Eigen::Vector3d newton_regressor;  // a_WBcm − g [m/s²]: multiplies m, per world axis
  Eigen::Vector3d newton_force;      // f_PB − Σ f_BC, world axes [N]
  Eigen::Matrix3d euler_regressor;   // S [1/s²]: multiplies (J11, J22, J33)
  Eigen::Vector3d euler_moment;      // N, body axes, about Bcm [N m]
};

// Throws std::invalid_argument "<what>: link 'X' axes are not principal axes"
// for a link with off-diagonal inertia.
void CheckPrincipalAxes(const RobotModel& model, const std::string& what);

PerBodyRows ComputePerBodyRows(const RobotModel& model, int body, const LogStep& step);

}  // namespace idbench
