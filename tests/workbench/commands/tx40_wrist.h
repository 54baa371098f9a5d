// The Stäubli TX40's transmission written out by hand (an independent check of
// engine/transmission.h): gear ratios N, motor 6 turning with joint 5
// (θm6 = N6·(q5 + q6)). Shared by the tests of the commands that read it.
#pragma once

#include <Eigen/Core>

namespace idbench::testing {

inline constexpr double kTx40Ratio[6] = {32, 32, 45, -48, 45, 32};

// θ̇m = A·q̇ for the TX40's A.
inline Eigen::VectorXd Tx40MotorRates(const Eigen::VectorXd& qd) {
  Eigen::VectorXd out(6);
  for (int j = 0; j < 5; ++j) out[j] = kTx40Ratio[j] * qd[j];
  out[5] = kTx40Ratio[5] * (qd[4] + qd[5]);
  return out;
}
// τ = Aᵀ·τm: τ5 = N5·τm5 + N6·τm6.
inline Eigen::VectorXd Tx40JointFromMotorTorques(const Eigen::VectorXd& tau_m) {
  Eigen::VectorXd out(6);
  for (int j = 0; j < 6; ++j) out[j] = kTx40Ratio[j] * tau_m[j];
  out[4] += kTx40Ratio[5] * tau_m[5];
  return out;
}
// τm = A⁻ᵀ·τ: τm6 = τ6/N6, τm5 = (τ5 − τ6)/N5.
inline Eigen::VectorXd Tx40MotorFromJointTorques(const Eigen::VectorXd& tau) {
  Eigen::VectorXd out(6);
  for (int j = 0; j < 6; ++j) out[j] = tau[j] / kTx40Ratio[j];
  out[4] = (tau[4] - tau[5]) / kTx40Ratio[4];
  return out;
}

}  // namespace idbench::testing
