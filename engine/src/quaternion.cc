#include "idbench/engine/quaternion.h"

#include <Eigen/Geometry>

namespace idbench {
namespace {

// Λ ⊗ (0, v).
Quaternion4 TimesPure(const Quaternion4& a, const Eigen::Vector3d& v) {
  const Eigen::Vector3d a_v = a.tail<3>();
  Quaternion4 out;
  out[0] = -a_v.dot(v);
  out.tail<3>() = a[0] * v + a_v.cross(v);
  return out;
}

}  // namespace

Quaternion4 QuaternionFromRotation(const Eigen::Matrix3d& R_WB) {
  Eigen::Quaterniond quat(R_WB);
  quat.normalize();
  Quaternion4 lambda(quat.w(), quat.x(), quat.y(), quat.z());
  return lambda[0] < 0.0 ? Quaternion4(-lambda) : lambda;
}

Eigen::Matrix3d RotationFromQuaternion(const Quaternion4& lambda) {
  return Eigen::Quaterniond(lambda[0], lambda[1], lambda[2], lambda[3]).normalized().toRotationMatrix();
}

Eigen::Matrix<double, 3, 4> QuaternionL(const Quaternion4& l) {
  Eigen::Matrix<double, 3, 4> L;
  L << -l[1], l[0], l[3], -l[2],  //
      -l[2], -l[3], l[0], l[1],   //
      -l[3], l[2], -l[1], l[0];
  return L;
}

QuaternionRates QuaternionRatesFromBodyRates(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& w_B,
                                             const Eigen::Vector3d& wd_B) {
  QuaternionRates rates;
  rates.lambda = QuaternionFromRotation(R_WB);
  rates.lambda_d = 0.5 * TimesPure(rates.lambda, w_B);
  rates.lambda_dd = 0.5 * (TimesPure(rates.lambda_d, w_B) + TimesPure(rates.lambda, wd_B));
  return rates;
}

}  // namespace idbench
