#include "idbench/ident/per_body_regressor.h"

#include <stdexcept>

namespace idbench {

Eigen::Matrix3d EulerRegressorQuaternion(const QuaternionRates& rates) {
  const Eigen::Matrix<double, 3, 4> L = QuaternionL(rates.lambda);
  const Eigen::Matrix<double, 3, 4> L_d = QuaternionL(rates.lambda_d);
  const Eigen::Vector3d L_lambda_dd = L * rates.lambda_dd;
  const Eigen::Vector3d L_lambda_d = L * rates.lambda_d;
  return 2.0 * Eigen::Matrix3d(L_lambda_dd.asDiagonal()) +
         4.0 * (L * L_d.transpose()) * L_lambda_d.asDiagonal();
}

void CheckPrincipalAxes(const RobotModel& model, const std::string& what) {
  for (const Link& link : model.links()) {
    const Eigen::Matrix3d& I = link.inertia.I_Bcm_B;
    if ((I - Eigen::Matrix3d(I.diagonal().asDiagonal())).norm() > 1e-12 * I.norm()) {
      throw std::invalid_argument(what + ": link '" + link.name +
                                  "' axes are not principal axes (off-diagonal inertia)");
    }
  }
}

PerBodyRows ComputePerBodyRows(const RobotModel& model, int body, const LogStep& step) {
  const size_t b = static_cast<size_t>(body);
  const BodySample& sample = step.body[b];
  const Link& link = model.link(body);
  PerBodyRows rows;

  // Newton: the inboard hinge pushes B, each child's hinge pulls it back.
  rows.newton_regressor = sample.a_WBcm_W - model.gravity_W();
  rows.newton_force = step.hinge[b].f_W;
  for (int c : model.children(body)) rows.newton_force -= step.hinge[static_cast<size_t>(c)].f_W;

  // Euler about the centroid, in body axes. Hinge points relative to Bcm are
  // known geometry: the inboard one at Bo, each child's at the origin of its J.
  const Eigen::Matrix3d R_WB = RotationFromQuaternion(sample.quaternion.lambda);
  const Eigen::Vector3d& p_BoBcm_B = link.inertia.p_BoBcm_B;
  const HingeWrench& inboard = step.hinge[b];
  Eigen::Vector3d N_B = (-p_BoBcm_B).cross(R_WB.transpose() * inboard.f_W) + R_WB.transpose() * inboard.m_Bo_W;
  for (int c : model.children(body)) {
    const HingeWrench& outboard = step.hinge[static_cast<size_t>(c)];
    const Eigen::Vector3d p_BcmCo_B = model.link(c).X_PJ.translation() - p_BoBcm_B;
    N_B -= p_BcmCo_B.cross(R_WB.transpose() * outboard.f_W) + R_WB.transpose() * outboard.m_Bo_W;
  }
  rows.euler_regressor = EulerRegressorQuaternion(sample.quaternion);
  rows.euler_moment = N_B;
  return rows;
}

}  // namespace idbench
