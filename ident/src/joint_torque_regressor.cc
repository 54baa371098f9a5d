#include "idbench/ident/joint_torque_regressor.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "idbench/engine/adjoint.h"
#include "number_format.h"

namespace idbench {
namespace {

// L = Lin(ω̇) + ω× Lin(ω), with I·w = Lin(w)·[Ixx, Ixy, Iyy, Ixz, Iyz, Izz]:
// I ω̇ + ω × I ω = L·[Ixx, …, Izz]. Written out entry by entry.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 6> InertiaTorqueMatrix(const Eigen::Matrix<Scalar, 3, 1>& w,
                                                const Eigen::Matrix<Scalar, 3, 1>& wd) {
  const Scalar &x = w.x(), &y = w.y(), &z = w.z();
  Eigen::Matrix<Scalar, 3, 6> L;
  L << wd.x(), wd.y() - z * x, -z * y, wd.z() + y * x, y * y - z * z, y * z,  //
      z * x, wd.x() + z * y, wd.y(), z * z - x * x, wd.z() - x * y, -x * z,   //
      -y * x, x * x - y * y, x * y, wd.x() - y * z, wd.y() + x * z, wd.z();
  return L;
}

// Rᵀ v, written out (a call to Eigen's product is not inlined at -O2).
template <typename Scalar>
[[gnu::always_inline]] inline Eigen::Matrix<Scalar, 3, 1> TransposeTimes(const Eigen::Matrix<Scalar, 3, 3>& R,
                                                                          const Eigen::Matrix<Scalar, 3, 1>& v) {
  return {R(0, 0) * v.x() + R(1, 0) * v.y() + R(2, 0) * v.z(),  //
          R(0, 1) * v.x() + R(1, 1) * v.y() + R(2, 1) * v.z(),  //
          R(0, 2) * v.x() + R(1, 2) * v.y() + R(2, 2) * v.z()};
}

// aᵀb, written out: Eigen's packet loads of 3-vectors just stored as scalars
// stall on store forwarding.
template <typename Scalar, typename A, typename B>
[[gnu::always_inline]] inline Scalar Dot3(const A& a, const B& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

std::optional<Transmission::SingleMotor> SingleMotorOf(const FrictionModel& friction, int j) {
  Transmission transmission;
  transmission.actuator_from_joint = friction.actuator_from_joint;
  return transmission.SingleMotorOf(j);
}

bool FrictionModel::IsValid(std::string* why) const {
  for (const auto& [field, speed] : {std::pair{"coulomb_smoothing", coulomb_smoothing},
                                     std::pair{"coulomb_min_speed", coulomb_min_speed}}) {
    if (speed >= 0.0 && std::isfinite(speed)) continue;
    if (why) *why = std::string(field) + ": expected >= 0 rad/s, got " + Shortest(speed);
    return false;
  }
  return true;
}

std::optional<FrictionModel> ParseFrictionTerms(const std::vector<std::string>& terms, std::string* why) {
  FrictionModel f;
  for (const std::string& term : terms) {
    if (term == "viscous") f.viscous = true;
    else if (term == "coulomb") f.coulomb = true;
    else if (term == "offset") f.offset = true;
    else if (term == "rotor") f.rotor_inertia = true;
    else if (term != "none" || terms.size() > 1) {
      if (why) *why = term == "none" ? "'none' cannot be combined with other terms"
                                     : "unknown term '" + term + "' (none, viscous, coulomb, offset, rotor)";
      return std::nullopt;
    }
  }
  return f;
}

int NumStandardParameters(const RobotModel& model, const FrictionModel& friction) {
  return model.n_links() * kInertialParametersPerLink + model.n_dof() * friction.per_joint();
}

std::vector<std::string> StandardParameterNames(const RobotModel& model, const FrictionModel& friction) {
  std::vector<std::string> names;
  for (const Link& link : model.links()) {
    for (const char* p : {"m", "mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"}) {
      names.push_back(link.name + "." + p);
    }
  }
  for (int j = 1; j <= model.n_dof(); ++j) {
    const std::string s = (friction.actuator_side() ? "m" : "") + std::to_string(j);
    if (friction.viscous) names.push_back("Fv" + s);
    if (friction.coulomb) names.push_back("Fc" + s);
    if (friction.offset) names.push_back("offset" + s);
    if (friction.rotor_inertia) names.push_back("Ia" + s);
  }
  return names;
}

Eigen::VectorXd StandardParameters(const RobotModel& model, const FrictionModel& friction) {
  Eigen::VectorXd pi = Eigen::VectorXd::Zero(NumStandardParameters(model, friction));
  for (int i = 0; i < model.n_links(); ++i) {
    const LinkInertia& in = model.link(i).inertia;
    const Eigen::Vector3d& c = in.p_BoBcm_B;
    const Eigen::Matrix3d I_Bo =
        in.I_Bcm_B + in.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    pi.segment<kInertialParametersPerLink>(kInertialParametersPerLink * i) << in.mass, in.mass * c.x(),
        in.mass * c.y(), in.mass * c.z(), I_Bo(0, 0), I_Bo(0, 1), I_Bo(1, 1), I_Bo(0, 2), I_Bo(1, 2), I_Bo(2, 2);
  }
  int k = model.n_links() * kInertialParametersPerLink;
  for (const Link& link : model.links()) {
    // The joint-side values where a motor drives a joint alone (else zero).
    JointDynamics dyn = link.dynamics;
    if (friction.actuator_side()) {
      const int j = static_cast<int>(&link - model.links().data());
      const std::optional<Transmission::SingleMotor> single = SingleMotorOf(friction, j);
      const double N = single ? single->ratio : 0.0;
      dyn = single ? JointDynamics{dyn.viscous / (N * N), dyn.coulomb / std::abs(N), dyn.rotor_inertia / (N * N)}
                   : JointDynamics{};
    }
    if (friction.viscous) pi[k++] = dyn.viscous;
    if (friction.coulomb) pi[k++] = dyn.coulomb;
    if (friction.offset) pi[k++] = 0.0;
    if (friction.rotor_inertia) pi[k++] = dyn.rotor_inertia;
  }
  return pi;
}

RobotModel ModelWithStandardParameters(const RobotModel& model, const FrictionModel& friction,
                                       const Eigen::VectorXd& pi) {
  if (pi.size() != NumStandardParameters(model, friction)) {
    throw std::invalid_argument("standard parameters: expected " + std::to_string(NumStandardParameters(model, friction)) +
                                " values, got " + std::to_string(pi.size()));
  }
  std::vector<Link> links = model.links();
  int k = model.n_links() * kInertialParametersPerLink;
  for (size_t i = 0; i < links.size(); ++i) {
    const auto p = pi.segment<kInertialParametersPerLink>(kInertialParametersPerLink * static_cast<Eigen::Index>(i));
    LinkInertia& in = links[i].inertia;
    in.mass = p[0];
    in.p_BoBcm_B = p.segment<3>(1) / p[0];
    Eigen::Matrix3d I_Bo;
    I_Bo << p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9];
    const Eigen::Vector3d& c = in.p_BoBcm_B;
    in.I_Bcm_B = I_Bo - p[0] * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    JointDynamics& dyn = links[i].dynamics;
    if (friction.viscous) dyn.viscous = pi[k++];
    if (friction.coulomb) dyn.coulomb = pi[k++];
    if (friction.offset) ++k;
    if (friction.rotor_inertia) dyn.rotor_inertia = pi[k++];
  }
  if (friction.actuator_side()) {
    // Motor k's terms on the joint it drives alone (Ia·N², Fv·N², Fc·|N|).
    std::vector<JointDynamics> motor(links.size());
    for (size_t k = 0; k < links.size(); ++k) motor[k] = links[k].dynamics;
    for (size_t j = 0; j < links.size(); ++j) {
      const std::optional<Transmission::SingleMotor> single = SingleMotorOf(friction, static_cast<int>(j));
      JointDynamics& dyn = links[j].dynamics;
      if (!single) {
        dyn = JointDynamics{};
        continue;
      }
      const double N = single->ratio;
      const JointDynamics& m = motor[static_cast<size_t>(single->motor)];
      if (friction.viscous) dyn.viscous = m.viscous * N * N;
      if (friction.coulomb) dyn.coulomb = m.coulomb * std::abs(N);
      if (friction.rotor_inertia) dyn.rotor_inertia = m.rotor_inertia * N * N;
    }
  }
  return RobotModel(model.name(), std::move(links), model.gravity_W(), model.ground());
}

namespace {

// Link i's own wrench about Bo, body axes, linear in its 10 parameters π_i:
//   f = m a + (ω̇× + ω×ω×) mc,   n = I ω̇ + ω × I ω − a × mc,  a = a_Bo − g,
// i.e. f = [a  K  0] π_i and n = [0  −a×  L] π_i with
//   K = ω̇× + ω ωᵀ − |ω|² 𝟙 (3×3),   L = Lin(ω̇) + ω× Lin(ω) (3×6).
template <typename Scalar>
struct LinkWrenchTerms {
  Eigen::Matrix<Scalar, 3, 1> a;
  Eigen::Matrix<Scalar, 3, 3> K;
  Eigen::Matrix<Scalar, 3, 6> L;
};

template <typename Scalar>
[[gnu::always_inline]] inline LinkWrenchTerms<Scalar> LinkTerms(const KinematicsData<Scalar>& d, size_t b, const Eigen::Matrix<Scalar, 3, 1>& g_W) {
  const Eigen::Matrix<Scalar, 3, 3>& R_WB = d.R_WB[b];
  const Eigen::Matrix<Scalar, 3, 1> w = TransposeTimes(R_WB, d.w_WB_W[b]);
  const Eigen::Matrix<Scalar, 3, 1> wd = TransposeTimes(R_WB, d.wd_WB_W[b]);
  LinkWrenchTerms<Scalar> t;
  t.a = TransposeTimes<Scalar>(R_WB, d.a_WBo_W[b] - g_W);
  t.K = w * w.transpose();
  const Scalar w2 = w.squaredNorm();
  t.K(0, 0) -= w2, t.K(1, 1) -= w2, t.K(2, 2) -= w2;
  t.K(0, 1) -= wd.z(), t.K(1, 0) += wd.z();
  t.K(0, 2) += wd.y(), t.K(2, 0) -= wd.y();
  t.K(1, 2) -= wd.x(), t.K(2, 1) += wd.x();
  t.L = InertiaTorqueMatrix(w, wd);
  return t;
}

// Joint j on the path from link i to the root carries link i's wrench:
//   τ_j = s_jᵀ (R n + r × R f) = uᵀ n + vᵀ f,  r = p_Bo_i − p_Jo_j,
// with the joint's axis u = Rᵀ s_j and moment arm v = Rᵀ (s_j × r) in B axes
// (f, n never leave B).
template <typename Scalar>
[[gnu::always_inline]] inline void JointArms(const KinematicsData<Scalar>& d, size_t b, size_t jj, Eigen::Matrix<Scalar, 3, 1>* u,
               Eigen::Matrix<Scalar, 3, 1>* v) {
  const Eigen::Matrix<Scalar, 3, 1>& s_W = d.axis_W[jj];
  *u = TransposeTimes(d.R_WB[b], s_W);
  *v = TransposeTimes<Scalar>(d.R_WB[b], s_W.cross(d.p_WBo_W[b] - d.p_WBo_W[jj]));
}

// Joint j's friction and drive columns, in π order (Fv, Fc, offset, Ia).
template <typename Scalar>
int FrictionColumns(const FrictionModel& friction, const Scalar& qd, const Scalar& qdd, Scalar* out) {
  int c = 0;
  if (friction.viscous) out[c++] = qd;
  if (friction.coulomb) {
    using std::tanh;
    if (std::abs(ValueOf(qd)) < friction.coulomb_min_speed) {
      out[c++] = Scalar(0.0);  // near rest: the sample says nothing of Fc
    } else if (friction.coulomb_smoothing > 0.0) {
      out[c++] = Scalar(tanh(qd / friction.coulomb_smoothing));
    } else {
      out[c++] = Scalar(double((ValueOf(qd) > 0.0) - (ValueOf(qd) < 0.0)));
    }
  }
  if (friction.offset) out[c++] = 1.0;
  if (friction.rotor_inertia) out[c++] = qdd;
  return c;
}

// Actuator side: visits each non-zero friction entry of Y, (joint j, column
// c, value A(k, j)·column of motor k), motor k's terms taken on its rates
// θ̇m_k = A_k·q̇ and θ̈m_k = A_k·q̈ (A_k row k of A), computed here once for
// both the regressor and its contraction.
template <typename Scalar, typename Visit>
void VisitActuatorFrictionEntries(const FrictionModel& friction, const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd, int base, Visit&& visit) {
  const Eigen::MatrixXd& A = friction.actuator_from_joint;
  const int n = static_cast<int>(A.rows()), per_joint = friction.per_joint();
  Scalar columns[4];
  for (int k = 0; k < n; ++k) {
    Scalar thetad(0.0), thetadd(0.0);
    for (int j = 0; j < n; ++j) {
      if (A(k, j) == 0.0) continue;
      thetad += A(k, j) * qd[j];
      thetadd += A(k, j) * qdd[j];
    }
    FrictionColumns(friction, thetad, thetadd, columns);
    for (int j = 0; j < n; ++j) {
      if (A(k, j) == 0.0) continue;
      for (int c = 0; c < per_joint; ++c) visit(j, base + per_joint * k + c, A(k, j) * columns[c]);
    }
  }
}

}  // namespace

template <typename Scalar>
void ComputeJointTorqueRegressorT(const RobotModel& model, const FrictionModel& friction,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd,
                                  KinematicsData<Scalar>* data,
                                  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>* Y) {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  ComputeKinematicsT<Scalar>(model, q, qd, qdd, data);
  const KinematicsData<Scalar>& d = *data;
  const int n = model.n_dof();
  // Blocks (joint j, link i) with j not on link i's path to the root stay zero.
  Y->setZero(n, NumStandardParameters(model, friction));
  const Vector3 g_W = model.gravity_W().template cast<Scalar>();
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    const LinkWrenchTerms<Scalar> t = LinkTerms(d, b, g_W);
    const int c = kInertialParametersPerLink * i;
    for (int j = i; j >= 0; j = model.link(j).parent) {  // each (joint, link) block written once
      Vector3 u, v;
      JointArms(d, b, static_cast<size_t>(j), &u, &v);
      const Vector3 a_x_u = t.a.cross(u);
      (*Y)(j, c) = Dot3<Scalar>(v, t.a);
      for (int k = 0; k < 3; ++k) (*Y)(j, c + 1 + k) = Dot3<Scalar>(v, t.K.col(k)) + a_x_u[k];
      for (int k = 0; k < 6; ++k) (*Y)(j, c + 4 + k) = Dot3<Scalar>(u, t.L.col(k));
    }
  }
  const int per_joint = friction.per_joint();
  if (per_joint == 0) return;
  const int base = model.n_links() * kInertialParametersPerLink;
  Scalar columns[4];
  if (friction.actuator_side()) {
    // Motor k's terms on θ̇m_k = A_k·q̇, into the joints through A_kᵀ.
    VisitActuatorFrictionEntries<Scalar>(friction, qd, qdd, base,
                                         [&](int j, int c, const Scalar& value) { (*Y)(j, c) = value; });
    return;
  }
  for (int j = 0; j < n; ++j) {
    FrictionColumns(friction, qd[j], qdd[j], columns);
    for (int k = 0; k < per_joint; ++k) (*Y)(j, base + per_joint * j + k) = columns[k];
  }
}

void ComputeJointTorqueOfParameters(const RobotModel& model, const FrictionModel& friction, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, const Eigen::VectorXd& pi,
                                    RobotData* data, Eigen::VectorXd* tau) {
  const int n = model.n_dof();
  if (pi.size() != NumStandardParameters(model, friction)) {
    throw std::invalid_argument("joint torque of parameters: expected " +
                                std::to_string(NumStandardParameters(model, friction)) +
                                " standard parameters, got " + std::to_string(pi.size()));
  }
  ComputeKinematicsT<double>(model, q, qd, qdd, data);
  const Eigen::Vector3d g_W = model.gravity_W();
  tau->setZero(n);
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    const LinkWrenchTerms<double> t = LinkTerms(*data, b, g_W);
    const auto p = pi.segment<kInertialParametersPerLink>(kInertialParametersPerLink * i);
    const Eigen::Vector3d h = p.segment<3>(1);
    // f = [a K 0] π_i, n = [0 −a× L] π_i (LinkWrenchTerms), both in B.
    const Eigen::Vector3d f = t.a * p[0] + t.K * h;
    const Eigen::Vector3d moment = t.L * p.segment<6>(4) - t.a.cross(h);
    for (int j = i; j >= 0; j = model.link(j).parent) {
      Eigen::Vector3d u, v;
      JointArms(*data, b, static_cast<size_t>(j), &u, &v);
      (*tau)[j] += Dot3<double>(v, f) + Dot3<double>(u, moment);
    }
  }
  const int per_joint = friction.per_joint();
  if (per_joint == 0) return;
  const int base = model.n_links() * kInertialParametersPerLink;
  if (friction.actuator_side()) {
    VisitActuatorFrictionEntries<double>(friction, qd, qdd, base,
                                         [&](int j, int c, double value) { (*tau)[j] += value * pi[c]; });
    return;
  }
  double columns[4];
  for (int j = 0; j < n; ++j) {
    FrictionColumns(friction, qd[j], qdd[j], columns);
    for (int k = 0; k < per_joint; ++k) (*tau)[j] += columns[k] * pi[base + per_joint * j + k];
  }
}

void ComputeJointSpaceInertia(const RobotModel& model, const FrictionModel& friction, const Eigen::VectorXd& pi,
                              const KinematicsData<double>& data, Eigen::MatrixXd* M) {
  const int n = model.n_dof();
  if (pi.size() != NumStandardParameters(model, friction)) {
    throw std::invalid_argument("joint-space inertia: expected " +
                                std::to_string(NumStandardParameters(model, friction)) + " standard parameters, got " +
                                std::to_string(pi.size()));
  }
  M->setZero(n, n);
  std::vector<int> path;  // link i's joints, i first, then towards the root
  std::vector<Eigen::Vector3d> u, v;
  for (int i = 0; i < model.n_links(); ++i) {
    const auto p = pi.segment<kInertialParametersPerLink>(kInertialParametersPerLink * i);
    const double m = p[0];
    const Eigen::Vector3d h = p.segment<3>(1);
    Eigen::Matrix3d I;
    I << p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9];
    path.clear(), u.clear(), v.clear();
    for (int j = i; j >= 0; j = model.link(j).parent) {
      path.push_back(j);
      u.emplace_back(), v.emplace_back();
      JointArms(data, static_cast<size_t>(i), static_cast<size_t>(j), &u.back(), &v.back());
    }
    for (size_t a = 0; a < path.size(); ++a) {
      const Eigen::Vector3d Iu = I * u[a];
      for (size_t b = 0; b <= a; ++b) {
        const double value = u[b].dot(Iu) + m * v[b].dot(v[a]) + h.dot(v[b].cross(u[a]) - u[b].cross(v[a]));
        (*M)(path[b], path[a]) += value;
        if (a != b) (*M)(path[a], path[b]) += value;
      }
    }
  }
  if (!friction.rotor_inertia) return;
  // The drive inertias: the only friction column with q̈ in it (FrictionColumns).
  const int base = model.n_links() * kInertialParametersPerLink;
  const int per_joint = friction.per_joint(), rotor = per_joint - 1;
  if (!friction.actuator_side()) {
    for (int j = 0; j < n; ++j) (*M)(j, j) += pi[base + per_joint * j + rotor];
    return;
  }
  // Motor k's Ia_k on θ̈m_k = A_k·q̈: Aᵀ diag(Ia) A.
  const Eigen::MatrixXd& A = friction.actuator_from_joint;
  for (int k = 0; k < n; ++k) M->noalias() += pi[base + per_joint * k + rotor] * A.row(k).transpose() * A.row(k);
}

template <typename Scalar>
Scalar ContractJointTorqueRegressorT(const RobotModel& model, const FrictionModel& friction,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& q,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qd,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& qdd,
                                     const Eigen::Ref<const Eigen::MatrixXd>& G, KinematicsData<Scalar>* data) {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  ComputeKinematicsT<Scalar>(model, q, qd, qdd, data);
  const KinematicsData<Scalar>& d = *data;
  const Vector3 g_W = model.gravity_W().template cast<Scalar>();
  Scalar sum(0.0);
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    const int c = kInertialParametersPerLink * i;
    // Σ_j G(j, block i) · Y(j, block i) gathered per link before the link's
    // own terms are formed: the G-weighted arms first (products with
    // constants), then one contraction with a, K, L.
    Vector3 arm_a = Vector3::Zero(), arm_u = Vector3::Zero();
    Eigen::Matrix<Scalar, 3, 3> arm_K = Eigen::Matrix<Scalar, 3, 3>::Zero();
    Eigen::Matrix<Scalar, 3, 6> arm_L = Eigen::Matrix<Scalar, 3, 6>::Zero();
    bool any = false;
    for (int j = i; j >= 0; j = model.link(j).parent) {
      const auto g = G.row(j).segment<kInertialParametersPerLink>(c);
      if (g.isZero()) continue;
      any = true;
      Vector3 u, v;
      JointArms(d, b, static_cast<size_t>(j), &u, &v);
      arm_a += g[0] * v;
      for (int k = 0; k < 3; ++k) arm_K.col(k) += g[1 + k] * v;
      arm_u += u.cross(Eigen::Vector3d(g[1], g[2], g[3]).template cast<Scalar>());  // g·(a × u) = a·(u × g)
      for (int k = 0; k < 6; ++k) arm_L.col(k) += g[4 + k] * u;
    }
    if (!any) continue;
    const LinkWrenchTerms<Scalar> t = LinkTerms(d, b, g_W);
    sum += Dot3<Scalar>(t.a, arm_a + arm_u);
    for (int k = 0; k < 3; ++k) sum += Dot3<Scalar>(t.K.col(k), arm_K.col(k));
    for (int k = 0; k < 6; ++k) sum += Dot3<Scalar>(t.L.col(k), arm_L.col(k));
  }
  const int per_joint = friction.per_joint();
  const int base = model.n_links() * kInertialParametersPerLink;
  Scalar columns[4];
  if (friction.actuator_side() && per_joint > 0) {
    VisitActuatorFrictionEntries<Scalar>(friction, qd, qdd, base,
                                         [&](int j, int c, const Scalar& value) { sum += G(j, c) * value; });
    return sum;
  }
  for (int j = 0; j < model.n_dof() && per_joint > 0; ++j) {
    FrictionColumns(friction, qd[j], qdd[j], columns);
    for (int k = 0; k < per_joint; ++k) sum += G(j, base + per_joint * j + k) * columns[k];
  }
  return sum;
}

void ComputeJointTorqueRegressor(const RobotModel& model, const FrictionModel& friction,
                                 const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                 const Eigen::VectorXd& qdd, RobotData* data, Eigen::MatrixXd* Y) {
  ComputeJointTorqueRegressorT<double>(model, friction, q, qd, qdd, data, Y);
}

template double ContractJointTorqueRegressorT<double>(const RobotModel&, const FrictionModel&, const Eigen::VectorXd&,
                                                     const Eigen::VectorXd&, const Eigen::VectorXd&,
                                                     const Eigen::Ref<const Eigen::MatrixXd>&,
                                                     KinematicsData<double>*);
template Adjoint ContractJointTorqueRegressorT<Adjoint>(
    const RobotModel&, const FrictionModel&, const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
    const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&, const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
    const Eigen::Ref<const Eigen::MatrixXd>&, KinematicsData<Adjoint>*);
template void ComputeJointTorqueRegressorT<Adjoint>(
    const RobotModel&, const FrictionModel&, const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
    const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&, const Eigen::Matrix<Adjoint, Eigen::Dynamic, 1>&,
    KinematicsData<Adjoint>*, Eigen::Matrix<Adjoint, Eigen::Dynamic, Eigen::Dynamic>*);

}  // namespace idbench
