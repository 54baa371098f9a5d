#include "idbench/engine/kinematics.h"

#include <stdexcept>
#include <string>

#include "idbench/engine/adjoint.h"

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

// Small products written out: Eigen's vectorised 3×3 kernels stall on
// values just stored, and the adjoint path records fewer operations when each
// entry is touched once (measured: the regressor's share of kinematics halves).
// A·v; v may be a constant double vector (then the products are cheaper).
template <typename Scalar, typename V>
[[gnu::always_inline]] inline Eigen::Matrix<Scalar, 3, 1> Times(const Eigen::Matrix<Scalar, 3, 3>& A, const V& v) {
  return {A(0, 0) * v.x() + A(0, 1) * v.y() + A(0, 2) * v.z(),  //
          A(1, 0) * v.x() + A(1, 1) * v.y() + A(1, 2) * v.z(),  //
          A(2, 0) * v.x() + A(2, 1) * v.y() + A(2, 2) * v.z()};
}

// A·B with A on the scalar and B a constant double matrix.
template <typename Scalar>
[[gnu::always_inline]] inline Eigen::Matrix<Scalar, 3, 3> TimesConstant(const Eigen::Matrix<Scalar, 3, 3>& A,
                                                                       const Eigen::Matrix3d& B) {
  Eigen::Matrix<Scalar, 3, 3> C;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) C(r, c) = A(r, 0) * B(0, c) + A(r, 1) * B(1, c) + A(r, 2) * B(2, c);
  }
  return C;
}

template <typename Scalar>
[[gnu::always_inline]] inline Eigen::Matrix<Scalar, 3, 1> Cross(const Eigen::Matrix<Scalar, 3, 1>& a,
                                                                const Eigen::Matrix<Scalar, 3, 1>& b) {
  return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

// R_WJ · Rot(axis, q) by Rodrigues' formula, Rot = 𝟙 + sin q K + (1 − cos q) K²
// with K = [axis]×: R_WJ + sin q (R_WJ K) + (1 − cos q)(R_WJ K²), where R_WJ K
// and R_WJ K² are products with constants.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> RotateAbout(const Eigen::Matrix<Scalar, 3, 3>& R_WJ, const Eigen::Vector3d& axis,
                                        const Scalar& angle) {
  using std::cos;
  using std::sin;
  Eigen::Matrix3d K;
  K << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  const Scalar s = sin(angle), one_minus_c = 1.0 - cos(angle);
  const Eigen::Matrix<Scalar, 3, 3> RK = TimesConstant(R_WJ, K), RK2 = TimesConstant(R_WJ, Eigen::Matrix3d(K * K));
  Eigen::Matrix<Scalar, 3, 3> R;
  for (int i = 0; i < 9; ++i) R.data()[i] = R_WJ.data()[i] + s * RK.data()[i] + one_minus_c * RK2.data()[i];
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
    static const Matrix3 kIdentity = Matrix3::Identity();
    static const Vector3 kZero = Vector3::Zero();
    const bool root = link.parent < 0;
    const size_t p = root ? 0 : static_cast<size_t>(link.parent);
    const Matrix3& R_WP = root ? kIdentity : d.R_WB[p];
    const Vector3& p_WPo = root ? kZero : d.p_WBo_W[p];
    const Vector3& w_P = root ? kZero : d.w_WB_W[p];
    const Vector3& wd_P = root ? kZero : d.wd_WB_W[p];
    const Vector3& v_Po = root ? kZero : d.v_WBo_W[p];
    const Vector3& a_Po = root ? kZero : d.a_WBo_W[p];
    // Pose: X_WB = X_WP · X_PJ · Rot(axis, q).
    const Matrix3 R_WJ = TimesConstant(R_WP, link.X_PJ.linear());
    d.R_WB[b] = RotateAbout(R_WJ, link.axis_J, q[i]);
    const Vector3 p_PoBo_W = Times(R_WP, link.X_PJ.translation());
    d.p_WBo_W[b] = p_WPo + p_PoBo_W;
    d.axis_W[b] = Times(R_WJ, link.axis_J);
    const Vector3 p_BoBcm_W = Times(d.R_WB[b], link.inertia.p_BoBcm_B);
    d.p_WBcm_W[b] = d.p_WBo_W[b] + p_BoBcm_W;

    // Velocities and accelerations: the hinge point is fixed in P.
    const Vector3& s = d.axis_W[b];
    d.w_WB_W[b] = w_P + s * qd[i];
    d.wd_WB_W[b] = wd_P + s * qdd[i] + Cross(w_P, s) * qd[i];
    d.v_WBo_W[b] = v_Po + Cross(w_P, p_PoBo_W);
    d.a_WBo_W[b] = a_Po + Cross(wd_P, p_PoBo_W) + Cross(w_P, Cross(w_P, p_PoBo_W));
    const Vector3& w = d.w_WB_W[b];
    d.a_WBcm_W[b] = d.a_WBo_W[b] + Cross(d.wd_WB_W[b], p_BoBcm_W) + Cross(w, Cross(w, p_BoBcm_W));
  }
}

void ComputeKinematics(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                       const Eigen::VectorXd& qdd, RobotData* data) {
  ComputeKinematicsT<double>(model, q, qd, qdd, data);
}

template struct KinematicsData<double>;
template struct KinematicsData<Adjoint>;
template void ComputeKinematicsT<double>(const RobotModel&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                         const Eigen::VectorXd&, KinematicsData<double>*);
template void ComputeKinematicsT<Adjoint>(const RobotModel&, const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
                                          const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
                                          const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&, KinematicsData<Adjoint>*);

}  // namespace idbench
