#include "idbench/ident/joint_torque_regressor.h"

#include <cmath>
#include <stdexcept>

namespace idbench {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// I·w = Lin(w)·[Ixx, Ixy, Iyy, Ixz, Iyz, Izz].
Eigen::Matrix<double, 3, 6> InertiaProductMatrix(const Eigen::Vector3d& w) {
  Eigen::Matrix<double, 3, 6> L;
  L << w.x(), w.y(), 0, w.z(), 0, 0,  //
      0, w.x(), w.y(), 0, w.z(), 0,   //
      0, 0, 0, w.x(), w.y(), w.z();
  return L;
}

}  // namespace

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
    const std::string s = std::to_string(j);
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
    if (friction.viscous) pi[k++] = link.dynamics.viscous;
    if (friction.coulomb) pi[k++] = link.dynamics.coulomb;
    if (friction.offset) pi[k++] = 0.0;
    if (friction.rotor_inertia) pi[k++] = link.dynamics.rotor_inertia;
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
  return RobotModel(model.name(), std::move(links), model.gravity_W());
}

void ComputeJointTorqueRegressor(const RobotModel& model, const FrictionModel& friction,
                                 const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                 const Eigen::VectorXd& qdd, RobotData* data, Eigen::MatrixXd* Y) {
  ComputeKinematics(model, q, qd, qdd, data);
  const RobotData& d = *data;
  const int n = model.n_dof();
  Y->setZero(n, NumStandardParameters(model, friction));
  const Eigen::Vector3d& g_W = model.gravity_W();
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    const Eigen::Matrix3d& R = d.R_WB[b];
    // Link i's own wrench about Bo, body axes, linear in its 10 parameters:
    //   f = m a + (ω̇× + ω×ω×) mc,   n = I ω̇ + ω × I ω − a × mc,  a = a_Bo − g.
    const Eigen::Vector3d w = R.transpose() * d.w_WB_W[b];
    const Eigen::Vector3d wd = R.transpose() * d.wd_WB_W[b];
    const Eigen::Vector3d a = R.transpose() * (d.a_WBo_W[b] - g_W);
    Eigen::Matrix<double, 3, 10> A_f = Eigen::Matrix<double, 3, 10>::Zero();
    Eigen::Matrix<double, 3, 10> A_n = Eigen::Matrix<double, 3, 10>::Zero();
    A_f.col(0) = a;
    A_f.block<3, 3>(0, 1) = Skew(wd) + Skew(w) * Skew(w);
    A_n.block<3, 3>(0, 1) = -Skew(a);
    A_n.block<3, 6>(0, 4) = InertiaProductMatrix(wd) + Skew(w) * InertiaProductMatrix(w);
    const Eigen::Matrix<double, 3, 10> F_W = R * A_f;
    const Eigen::Matrix<double, 3, 10> N_W = R * A_n;
    // Every joint j on the path from link i to the root carries that wrench:
    // τ_j += s_jᵀ (n + (p_Bo_i − p_Jo_j) × f).
    for (int j = i; j >= 0; j = model.link(j).parent) {
      const size_t jj = static_cast<size_t>(j);
      const Eigen::RowVector3d s = d.axis_W[jj].transpose();
      const Eigen::Vector3d r = d.p_WBo_W[b] - d.p_WBo_W[jj];
      Y->block<1, 10>(j, kInertialParametersPerLink * i) += s * N_W + (s * Skew(r)) * F_W;
    }
  }
  // Friction and drive terms, per joint.
  const int k = friction.per_joint();
  if (k == 0) return;
  const int base = model.n_links() * kInertialParametersPerLink;
  for (int j = 0; j < n; ++j) {
    int c = base + k * j;
    if (friction.viscous) (*Y)(j, c++) = qd[j];
    if (friction.coulomb) {
      (*Y)(j, c++) = friction.coulomb_smoothing > 0.0 ? std::tanh(qd[j] / friction.coulomb_smoothing)
                                                      : (qd[j] > 0.0) - (qd[j] < 0.0);
    }
    if (friction.offset) (*Y)(j, c++) = 1.0;
    if (friction.rotor_inertia) (*Y)(j, c++) = qdd[j];
  }
}

}  // namespace idbench
