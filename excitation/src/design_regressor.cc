#include "idbench/excitation/design_regressor.h"

#include <random>
#include <stdexcept>

#include "idbench/ident/least_squares.h"
#include "idbench/ident/per_body_regressor.h"

namespace idbench {
namespace {

constexpr int kRowsPerBody = 6;  // 3 Newton rows (world axes), 3 Euler rows (body axes)
const char* const kMomentNames[3] = {"J11", "J22", "J33"};

}  // namespace

DesignRegressor::Workspace::Workspace(const RobotModel& model)
    : kinematics(model),
      adjoint_kinematics(model),
      q(model.n_dof()),
      qd(model.n_dof()),
      qdd(model.n_dof()) {}

DesignRegressor DesignRegressor::JointTorque(const RobotModel& model, const FrictionModel& friction,
                                             const BaseParameterOptions& base_options) {
  DesignRegressor r(model, IdentificationModel::kJointTorque);
  r.friction_ = friction;
  r.base_ = ComputeBaseParameters(model, friction, base_options);
  r.rows_per_sample_ = model.n_dof();
  r.names_ = r.base_.names;
  r.true_parameters_ = r.base_.combination * StandardParameters(model, friction);
  return r;
}

DesignRegressor DesignRegressor::PerBody(const RobotModel& model) {
  CheckPrincipalAxes(model, "per-body design");
  DesignRegressor r(model, IdentificationModel::kPerBody);
  const int n = model.n_dof();
  r.rows_per_sample_ = kRowsPerBody * model.n_links();
  // Which principal moments any motion can identify: the Euler rows of each
  // body stacked over seeded random states, classified by rank-revealing
  // least squares (the per-body identifier's own test).
  constexpr int kStates = 60;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  KinematicsData<double> k(model);
  std::vector<Eigen::MatrixXd> euler(static_cast<size_t>(model.n_links()), Eigen::MatrixXd(3 * kStates, 3));
  Eigen::VectorXd q(n), qd(n), qdd(n);
  for (int s = 0; s < kStates; ++s) {
    for (int j = 0; j < n; ++j) {
      q[j] = 3.14159 * u(rng);
      qd[j] = 3.0 * u(rng);
      qdd[j] = 10.0 * u(rng);
    }
    ComputeKinematicsT<double>(model, q, qd, qdd, &k);
    for (int b = 0; b < model.n_links(); ++b) {
      const Eigen::Matrix3d& R = k.R_WB[static_cast<size_t>(b)];
      const Eigen::Vector3d w = R.transpose() * k.w_WB_W[static_cast<size_t>(b)];
      const Eigen::Vector3d wd = R.transpose() * k.wd_WB_W[static_cast<size_t>(b)];
      euler[static_cast<size_t>(b)].middleRows<3>(3 * s) = EulerRegressorOmega(w, wd);
    }
  }
  for (int b = 0; b < model.n_links(); ++b) {
    const Link& link = model.link(b);
    const LeastSquaresSolution ls =
        SolveLeastSquares(euler[static_cast<size_t>(b)], Eigen::VectorXd::Zero(3 * kStates));
    r.col_m_.push_back(static_cast<int>(r.names_.size()));
    r.names_.push_back(link.name + ".m");
    std::vector<double> truth{link.inertia.mass};
    r.col_J_.emplace_back(3, -1);
    for (int a = 0; a < 3; ++a) {
      if (!ls.identifiable[static_cast<size_t>(a)]) continue;
      r.col_J_.back()[static_cast<size_t>(a)] = static_cast<int>(r.names_.size());
      r.names_.push_back(link.name + "." + kMomentNames[a]);
    }
    for (int a = 0; a < 3; ++a) {
      if (r.col_J_.back()[static_cast<size_t>(a)] >= 0) truth.push_back(link.inertia.I_Bcm_B(a, a));
    }
    r.true_parameters_.conservativeResize(static_cast<Eigen::Index>(r.names_.size()));
    for (size_t i = 0; i < truth.size(); ++i) {
      r.true_parameters_[static_cast<Eigen::Index>(r.names_.size() - truth.size() + i)] = truth[i];
    }
  }
  return r;
}

template <typename Scalar>
void DesignRegressor::PerBodyRows(const KinematicsData<Scalar>& k,
                                  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>* rows) const {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  rows->setZero(rows_per_sample_, n_parameters());
  const Vector3 g_W = model_->gravity_W().template cast<Scalar>();
  for (int b = 0; b < model_->n_links(); ++b) {
    const size_t i = static_cast<size_t>(b);
    rows->template block<3, 1>(kRowsPerBody * b, col_m_[i]) = k.a_WBcm_W[i] - g_W;
    const Vector3 w = k.R_WB[i].transpose() * k.w_WB_W[i];
    const Vector3 wd = k.R_WB[i].transpose() * k.wd_WB_W[i];
    const Eigen::Matrix<Scalar, 3, 3> S = EulerRegressorOmega<Scalar>(w, wd);
    for (int a = 0; a < 3; ++a) {
      const int c = col_J_[i][static_cast<size_t>(a)];
      if (c >= 0) rows->template block<3, 1>(kRowsPerBody * b + 3, c) = S.col(a);
    }
  }
}

void DesignRegressor::Rows(const JointState& x, Workspace* ws, Eigen::Ref<Eigen::MatrixXd> rows) const {
  if (kind_ == IdentificationModel::kJointTorque) {
    ComputeJointTorqueRegressorT<double>(*model_, friction_, x.q, x.qd, x.qdd, &ws->kinematics, &ws->Y);
    for (int c = 0; c < n_parameters(); ++c) rows.col(c) = ws->Y.col(base_.independent[static_cast<size_t>(c)]);
    return;
  }
  ComputeKinematicsT<double>(*model_, x.q, x.qd, x.qdd, &ws->kinematics);
  PerBodyRows<double>(ws->kinematics, &ws->Y);
  rows = ws->Y;
}

void DesignRegressor::StateGradient(const JointState& x, const Eigen::Ref<const Eigen::MatrixXd>& G,
                                    Workspace* ws, Eigen::Ref<Eigen::VectorXd> g) const {
  const int n = model_->n_dof();
  const bool torque = kind_ == IdentificationModel::kJointTorque;
  if (torque) {
    // G on the standard columns: the base rows are Y's independent columns.
    ws->G_standard.setZero(n, NumStandardParameters(*model_, friction_));
    for (int c = 0; c < n_parameters(); ++c) ws->G_standard.col(base_.independent[static_cast<size_t>(c)]) = G.col(c);
  }
  // Record ⟨G, Rows(x)⟩ on the tape with the 3n state entries as inputs,
  // then one backward sweep.
  AdjointTape& tape = ws->tape;
  tape.Clear();
  for (int j = 0; j < n; ++j) ws->q[j] = tape.Input(x.q[j]);
  for (int j = 0; j < n; ++j) ws->qd[j] = tape.Input(x.qd[j]);
  for (int j = 0; j < n; ++j) ws->qdd[j] = tape.Input(x.qdd[j]);
  Adjoint sum(0.0);
  if (torque) {
    sum = ContractJointTorqueRegressorT<Adjoint>(*model_, friction_, ws->q, ws->qd, ws->qdd, ws->G_standard,
                                                 &ws->adjoint_kinematics);
  } else {
    ComputeKinematicsT<Adjoint>(*model_, ws->q, ws->qd, ws->qdd, &ws->adjoint_kinematics);
    PerBodyRows<Adjoint>(ws->adjoint_kinematics, &ws->adjoint_Y);
    for (int c = 0; c < n_parameters(); ++c) {
      for (int r = 0; r < rows_per_sample_; ++r) {
        if (G(r, c) != 0.0) sum += G(r, c) * ws->adjoint_Y(r, c);
      }
    }
  }
  tape.Backward(sum);
  for (int j = 0; j < n; ++j) {
    g[j] = tape.adjoint(ws->q[j]);
    g[n + j] = tape.adjoint(ws->qd[j]);
    g[2 * n + j] = tape.adjoint(ws->qdd[j]);
  }
}

Eigen::MatrixXd DesignRegressor::Stack(const Trajectory& trajectory, const std::vector<double>& times) const {
  Workspace ws(*model_);
  Eigen::MatrixXd W(rows_per_sample_ * static_cast<Eigen::Index>(times.size()), n_parameters());
  JointState x(model_->n_dof());
  for (size_t s = 0; s < times.size(); ++s) {
    trajectory.Evaluate(times[s], &x);
    Rows(x, &ws, W.middleRows(rows_per_sample_ * static_cast<Eigen::Index>(s), rows_per_sample_));
  }
  return W;
}

}  // namespace idbench
