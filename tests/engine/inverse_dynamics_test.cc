#include "idbench/engine/inverse_dynamics.h"

#include <gtest/gtest.h>

#include <random>

#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using testing::RandomVector;

// Total mechanical energy: Σ ½ m |v_cm|² + ½ ωᵀ I_W ω − m g·p_cm.
double Energy(const RobotModel& model, const RobotData& d) {
  double e = 0.0;
  for (int i = 0; i < model.n_links(); ++i) {
    const size_t b = static_cast<size_t>(i);
    const LinkInertia& I = model.link(i).inertia;
    const Eigen::Vector3d v_cm = d.v_WBo_W[b] + d.w_WB_W[b].cross(d.p_WBcm_W[b] - d.p_WBo_W[b]);
    const Eigen::Matrix3d I_W = d.R_WB[b] * I.I_Bcm_B * d.R_WB[b].transpose();
    e += 0.5 * I.mass * v_cm.squaredNorm() + 0.5 * d.w_WB_W[b].dot(I_W * d.w_WB_W[b]) -
         I.mass * model.gravity_W().dot(d.p_WBcm_W[b]);
  }
  return e;
}

// Power balance, an identity independent of the recursion: dE/dt = τ · qd.
TEST(InverseDynamicsTest, PowerEqualsRateOfEnergy) {
  const RobotModel model = MakePaper6r();
  RobotData d(model), dp(model), dm(model);
  std::mt19937 rng(11);
  const int n = model.n_dof();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 1.0, &rng),
                          qdd = RandomVector(n, 3.0, &rng);
    const Eigen::VectorXd tau = InverseDynamics(model, q, qd, qdd, &d);
    const double h = 1e-5;
    ComputeKinematics(model, q + qd * h + 0.5 * qdd * h * h, qd + qdd * h, qdd, &dp);
    ComputeKinematics(model, q - qd * h + 0.5 * qdd * h * h, qd - qdd * h, qdd, &dm);
    const double power_fd = (Energy(model, dp) - Energy(model, dm)) / (2 * h);
    const double power = tau.dot(qd);
    EXPECT_NEAR(power_fd, power, 1e-6 * tau.cwiseAbs().sum()) << "trial " << trial;
  }
}

// At rest the base hinge carries the whole weight, and each joint torque is
// the gravity moment of everything outboard about that hinge's axis.
TEST(InverseDynamicsTest, StaticWrenchesAreWeights) {
  const RobotModel model = MakePaper6r();
  RobotData d(model);
  std::mt19937 rng(12);
  const Eigen::VectorXd q = RandomVector(6, 3.0, &rng), zero = Eigen::VectorXd::Zero(6);
  InverseDynamics(model, q, zero, zero, &d);
  for (int i = 0; i < 6; ++i) {
    Eigen::Vector3d weight = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
    for (int k = i; k < 6; ++k) {
      const Eigen::Vector3d w = -model.link(k).inertia.mass * model.gravity_W();
      weight += w;
      moment += (d.p_WBcm_W[static_cast<size_t>(k)] - d.p_WBo_W[static_cast<size_t>(i)]).cross(w);
    }
    EXPECT_LT((d.f_PB_W[static_cast<size_t>(i)] - weight).norm(), 1e-12 * weight.norm());
    EXPECT_LT((d.m_PB_Bo_W[static_cast<size_t>(i)] - moment).norm(), 1e-12 * (1 + moment.norm()));
    EXPECT_NEAR(d.tau[i], d.axis_W[static_cast<size_t>(i)].dot(moment), 1e-12 * (1 + moment.norm()));
  }
}

}  // namespace
}  // namespace idbench
