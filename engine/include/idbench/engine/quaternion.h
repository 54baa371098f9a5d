// Orientation quaternions in the paper's convention (paper-method.md):
// Λ = (λ0, λ1, λ2, λ3), scalar first, Hamilton product, A(Λ) maps body axes
// to world axes. Body-frame rates: ω = 2 L(Λ) Λ', ω̇ = 2 L(Λ) Λ''.
#pragma once

#include <Eigen/Core>

namespace idbench {

using Quaternion4 = Eigen::Vector4d;  // (λ0, λ1, λ2, λ3)

// Λ of the rotation R_WB, with λ0 >= 0.
Quaternion4 QuaternionFromRotation(const Eigen::Matrix3d& R_WB);
Eigen::Matrix3d RotationFromQuaternion(const Quaternion4& lambda);

// L(Λ) = [-λ1 λ0 λ3 -λ2; -λ2 -λ3 λ0 λ1; -λ3 λ2 -λ1 λ0] (the paper's R*).
Eigen::Matrix<double, 3, 4> QuaternionL(const Quaternion4& lambda);

struct QuaternionRates {
  Quaternion4 lambda;     // Λ
  Quaternion4 lambda_d;   // Λ'  [1/s]
  Quaternion4 lambda_dd;  // Λ'' [1/s²]
};

// Λ, Λ' = ½ Λ ⊗ (0, ω_B), Λ'' = ½ (Λ' ⊗ (0, ω_B) + Λ ⊗ (0, ω̇_B)).
QuaternionRates QuaternionRatesFromBodyRates(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& w_B,
                                             const Eigen::Vector3d& wd_B);

}  // namespace idbench
