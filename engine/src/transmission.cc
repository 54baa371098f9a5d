#include "idbench/engine/transmission.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <string>

namespace idbench {

Transmission Transmission::FromReduction(const std::vector<double>& reduction) {
  Transmission out;
  out.actuator_from_joint = Eigen::Map<const Eigen::VectorXd>(reduction.data(), static_cast<Eigen::Index>(reduction.size()))
                                .asDiagonal();
  return out;
}

bool Transmission::IsValid(int n, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  const Eigen::MatrixXd& A = actuator_from_joint;
  if (A.rows() != n || A.cols() != n) {
    return fail("actuator_from_joint: expected " + std::to_string(n) + " × " + std::to_string(n) + " (one row per "
                "actuator, one column per joint), got " + std::to_string(A.rows()) + " × " + std::to_string(A.cols()));
  }
  if (!A.allFinite()) return fail("actuator_from_joint: expected finite numbers");
  // Bounded before the SVD: a ratio of 1e77 overflowed the regressor (N²) downstream.
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      if (std::abs(A(k, j)) > kMaxRatio) {
        char text[64];
        std::snprintf(text, sizeof(text), "%g", A(k, j));
        return fail("actuator_from_joint[" + std::to_string(k) + "][" + std::to_string(j) + "]: " + text +
                    " rad of motor " + std::to_string(k + 1) + " per rad of joint " + std::to_string(j + 1) +
                    ", beyond any drive (a gear ratio of magnitude at most 10000)");
      }
    }
  }
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  if (n > 0 && !(sigma[n - 1] > 1e-12 * sigma[0])) {
    return fail("actuator_from_joint: not invertible (a joint no motor turns, or two motors turning as one)");
  }
  if (n > 0 && sigma[n - 1] < 1.0 / kMaxRatio) {
    char text[64];
    std::snprintf(text, sizeof(text), "%g", sigma[n - 1]);
    return fail("actuator_from_joint: smallest singular value " + std::string(text) + ", below 1/10000: a joint "
                "would turn more than 10000 rad per rad of its motors, beyond any drive");
  }
  if (joint_offset.size() != 0 && joint_offset.size() != n) {
    return fail("joint_offset: expected " + std::to_string(n) + " values, got " + std::to_string(joint_offset.size()));
  }
  if (!joint_offset.allFinite()) return fail("joint_offset: expected finite numbers");
  return true;
}

Eigen::MatrixXd Transmission::JointRates(const Eigen::MatrixXd& thetad_m) const {
  // Rows: q̇ᵀ = θ̇mᵀ·A⁻ᵀ, i.e. Aᵀ·... solved per block: (A·Q̇ᵀ = Θ̇ᵀ).
  return actuator_from_joint.partialPivLu().solve(thetad_m.transpose()).transpose();
}

Eigen::MatrixXd Transmission::JointPositions(const Eigen::MatrixXd& theta_m) const {
  Eigen::MatrixXd q = JointRates(theta_m);
  if (joint_offset.size() > 0) q.rowwise() += joint_offset.transpose();
  return q;
}

Eigen::MatrixXd Transmission::JointTorques(const Eigen::MatrixXd& tau_m) const {
  return tau_m * actuator_from_joint;  // rows: τᵀ = τmᵀ·A
}

std::optional<Transmission::SingleMotor> Transmission::SingleMotorOf(int j) const {
  const Eigen::MatrixXd& A = actuator_from_joint;
  int motor = -1;
  for (int k = 0; k < A.rows(); ++k) {
    if (A(k, j) == 0.0) continue;
    if (motor >= 0) return std::nullopt;
    motor = k;
  }
  if (motor < 0) return std::nullopt;
  for (int c = 0; c < A.cols(); ++c) {
    if (c != j && A(motor, c) != 0.0) return std::nullopt;
  }
  return SingleMotor{motor, A(motor, j)};
}

}  // namespace idbench
