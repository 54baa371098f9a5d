#include "idbench/engine/inverse_dynamics.h"

namespace idbench {

const Eigen::VectorXd& InverseDynamics(const RobotModel& model, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                       RobotData* data) {
  ComputeKinematics(model, q, qd, qdd, data);
  RobotData& d = *data;
  const Eigen::Vector3d& g_W = model.gravity_W();
  // Backward pass, leaves first (parents have smaller indices).
  for (int i = model.n_links() - 1; i >= 0; --i) {
    const size_t b = static_cast<size_t>(i);
    const LinkInertia& inertia = model.link(i).inertia;
    const Eigen::Matrix3d& R_WB = d.R_WB[b];
    const Eigen::Vector3d w_B = R_WB.transpose() * d.w_WB_W[b];
    const Eigen::Vector3d wd_B = R_WB.transpose() * d.wd_WB_W[b];
    // Net force and moment about the centre of mass needed by the link itself.
    const Eigen::Vector3d f_net_W = inertia.mass * (d.a_WBcm_W[b] - g_W);
    const Eigen::Vector3d m_Bcm_W =
        R_WB * (inertia.I_Bcm_B * wd_B + w_B.cross(inertia.I_Bcm_B * w_B));
    Eigen::Vector3d f_W = f_net_W;
    Eigen::Vector3d m_Bo_W = m_Bcm_W + (d.p_WBcm_W[b] - d.p_WBo_W[b]).cross(f_net_W);
    // Plus what the hinge passes on to each child C (acting at Co).
    for (int c : model.children(i)) {
      const size_t cc = static_cast<size_t>(c);
      f_W += d.f_PB_W[cc];
      m_Bo_W += d.m_PB_Bo_W[cc] + (d.p_WBo_W[cc] - d.p_WBo_W[b]).cross(d.f_PB_W[cc]);
    }
    d.f_PB_W[b] = f_W;
    d.m_PB_Bo_W[b] = m_Bo_W;
    d.tau[i] = d.axis_W[b].dot(m_Bo_W);
  }
  return d.tau;
}

void AddJointDynamicsTorque(const RobotModel& model, const Eigen::VectorXd& qd,
                            const Eigen::VectorXd& qdd, Eigen::VectorXd* tau) {
  for (int j = 0; j < model.n_dof(); ++j) {
    const JointDynamics& dyn = model.link(j).dynamics;
    const double sign = (qd[j] > 0.0) - (qd[j] < 0.0);
    (*tau)[j] += dyn.viscous * qd[j] + dyn.coulomb * sign + dyn.rotor_inertia * qdd[j];
  }
}

}  // namespace idbench
