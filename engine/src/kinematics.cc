#include "idbench/engine/kinematics.h"

#include <stdexcept>
#include <string>

#include "idbench/engine/dual.h"

namespace idbench {

template <typename Scalar>
KinematicsData<Scalar>::KinematicsData(const RobotModel& model) {
  const size_t n = static_cast<size_t>(model.n_links());
  for (auto* v : {&p_WBo_W, &p_WBcm_W, &axis_W, &w_WB_W, &wd_WB_W, &v_WBo_W, &a_WBo_W, &a_WBcm_W}) {
    v->assign(n, Vector3::Zero());
  }
  R_WB.assign(n, Matrix3::Identity());
}

RobotData::RobotData(const RobotModel& model) : KinematicsData<double>(model) {
  const size_t n = static_cast<size_t>(model.n_links());
  f_PB_W.assign(n, Eigen::Vector3d::Zero());
  m_PB_Bo_W.assign(n, Eigen::Vector3d::Zero());
  tau = Eigen::VectorXd::Zero(model.n_dof());
}

namespace {

template <typename Vector>
void CheckSize(const char* what, const Vector& v, int n) {
  if (v.size() != n) {
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n) +
                                " entries, got " + std::to_string(v.size()));
  }
}

// Rot(axis, angle) by Rodrigues' formula (works on any scalar).
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> AxisRotation(const Eigen::Vector3d& axis, const Scalar& angle) {
  using std::cos;
  using std::sin;
  Eigen::Matrix3d K;
  K << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  const Scalar s = sin(angle), c = cos(angle);
  Eigen::Matrix<Scalar, 3, 3> R;
  const Eigen::Matrix3d K2 = K * K;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) R(r, k) = (r == k ? 1.0 : 0.0) + s * K(r, k) + (1.0 - c) * K2(r, k);
  }
  return R;
}

}  // namespace

template <typename Scalar>
void ComputeKinematicsT(const RobotModel& model, const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd, KinematicsData<Scalar>* data) {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  const int n = model.n_dof();
  CheckSize("q", q, n);
  CheckSize("qd", qd, n);
  CheckSize("qdd", qdd, n);
  KinematicsData<Scalar>& d = *data;
  for (int i = 0; i < n; ++i) {
    const Link& link = model.link(i);
    const size_t b = static_cast<size_t>(i);
    // Parent state; the ground is fixed at the world origin.
    Matrix3 R_WP = Matrix3::Identity();
    Vector3 p_WPo = Vector3::Zero(), w_P = Vector3::Zero(), wd_P = Vector3::Zero(), v_Po = Vector3::Zero(),
            a_Po = Vector3::Zero();
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
    const Matrix3 R_WJ = R_WP * link.X_PJ.linear().template cast<Scalar>();
    d.R_WB[b] = R_WJ * AxisRotation(link.axis_J, q[i]);
    const Vector3 p_PoBo_W = R_WP * link.X_PJ.translation().template cast<Scalar>();
    d.p_WBo_W[b] = p_WPo + p_PoBo_W;
    d.axis_W[b] = R_WJ * link.axis_J.template cast<Scalar>();
    const Vector3 p_BoBcm_W = d.R_WB[b] * link.inertia.p_BoBcm_B.template cast<Scalar>();
    d.p_WBcm_W[b] = d.p_WBo_W[b] + p_BoBcm_W;

    // Velocities and accelerations: the hinge point is fixed in P.
    const Vector3& s = d.axis_W[b];
    d.w_WB_W[b] = w_P + s * qd[i];
    d.wd_WB_W[b] = wd_P + s * qdd[i] + w_P.cross(s) * qd[i];
    d.v_WBo_W[b] = v_Po + w_P.cross(p_PoBo_W);
    d.a_WBo_W[b] = a_Po + wd_P.cross(p_PoBo_W) + w_P.cross(w_P.cross(p_PoBo_W));
    const Vector3& w = d.w_WB_W[b];
    d.a_WBcm_W[b] = d.a_WBo_W[b] + d.wd_WB_W[b].cross(p_BoBcm_W) + w.cross(w.cross(p_BoBcm_W));
  }
}

void ComputeKinematics(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                       const Eigen::VectorXd& qdd, RobotData* data) {
  ComputeKinematicsT<double>(model, q, qd, qdd, data);
}

template struct KinematicsData<double>;
template struct KinematicsData<DualState>;
template void ComputeKinematicsT<double>(const RobotModel&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                         const Eigen::VectorXd&, KinematicsData<double>*);
template void ComputeKinematicsT<DualState>(const RobotModel&, const Eigen::Matrix<DualState, Eigen::Dynamic, 1>&,
                                            const Eigen::Matrix<DualState, Eigen::Dynamic, 1>&,
                                            const Eigen::Matrix<DualState, Eigen::Dynamic, 1>&,
                                            KinematicsData<DualState>*);

}  // namespace idbench
