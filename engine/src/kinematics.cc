#include "idbench/engine/kinematics.h"

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace idbench {

RobotData::RobotData(const RobotModel& model) {
  const size_t n = static_cast<size_t>(model.n_links());
  for (auto* v : {&p_WBo_W, &p_WBcm_W, &axis_W, &w_WB_W, &wd_WB_W, &v_WBo_W, &a_WBo_W, &a_WBcm_W,
                  &f_PB_W, &m_PB_Bo_W}) {
    v->assign(n, Eigen::Vector3d::Zero());
  }
  R_WB.assign(n, Eigen::Matrix3d::Identity());
  tau = Eigen::VectorXd::Zero(model.n_dof());
}

namespace {

void CheckSize(const char* what, const Eigen::VectorXd& v, int n) {
  if (v.size() != n) {
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n) +
                                " entries, got " + std::to_string(v.size()));
  }
}

}  // namespace

void ComputeKinematics(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                       const Eigen::VectorXd& qdd, RobotData* data) {
  const int n = model.n_dof();
  CheckSize("q", q, n);
  CheckSize("qd", qd, n);
  CheckSize("qdd", qdd, n);
  RobotData& d = *data;
  for (int i = 0; i < n; ++i) {
    const Link& link = model.link(i);
    const size_t b = static_cast<size_t>(i);
    // Parent state; the ground is fixed at the world origin.
    Eigen::Matrix3d R_WP = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_WPo = Eigen::Vector3d::Zero(), w_P = Eigen::Vector3d::Zero(),
                    wd_P = Eigen::Vector3d::Zero(), v_Po = Eigen::Vector3d::Zero(),
                    a_Po = Eigen::Vector3d::Zero();
    if (link.parent >= 0) {
      const size_t p = static_cast<size_t>(link.parent);
      R_WP = d.R_WB[p];
      p_WPo = d.p_WBo_W[p];
      w_P = d.w_WB_W[p];
      wd_P = d.wd_WB_W[p];
      v_Po = d.v_WBo_W[p];
      a_Po = d.a_WBo_W[p];
    }
    // Pose: X_WB = X_WP · X_PJ · Rot(axis, q).
    const Eigen::Matrix3d R_WJ = R_WP * link.X_PJ.linear();
    d.R_WB[b] = R_WJ * Eigen::AngleAxisd(q[i], link.axis_J).toRotationMatrix();
    const Eigen::Vector3d p_PoBo_W = R_WP * link.X_PJ.translation();
    d.p_WBo_W[b] = p_WPo + p_PoBo_W;
    d.axis_W[b] = R_WJ * link.axis_J;
    const Eigen::Vector3d p_BoBcm_W = d.R_WB[b] * link.inertia.p_BoBcm_B;
    d.p_WBcm_W[b] = d.p_WBo_W[b] + p_BoBcm_W;

    // Velocities and accelerations: the hinge point is fixed in P.
    const Eigen::Vector3d& s = d.axis_W[b];
    d.w_WB_W[b] = w_P + s * qd[i];
    d.wd_WB_W[b] = wd_P + s * qdd[i] + w_P.cross(s) * qd[i];
    d.v_WBo_W[b] = v_Po + w_P.cross(p_PoBo_W);
    d.a_WBo_W[b] = a_Po + wd_P.cross(p_PoBo_W) + w_P.cross(w_P.cross(p_PoBo_W));
    const Eigen::Vector3d& w = d.w_WB_W[b];
    d.a_WBcm_W[b] = d.a_WBo_W[b] + d.wd_WB_W[b].cross(p_BoBcm_W) + w.cross(w.cross(p_BoBcm_W));
  }
}

}  // namespace idbench
