#include "idbench/ident/per_body_regressor.h"

#include "idbench/engine/simulation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>

#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

TEST(PerBodyRegressorTest, QuaternionFormEqualsOmegaForm) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Matrix3d R = Eigen::AngleAxisd(u(rng), axis).toRotationMatrix();
    const Eigen::Vector3d w(u(rng), u(rng), u(rng)), wd(3 * u(rng), 3 * u(rng), 3 * u(rng));
    const Eigen::Matrix3d S_q = EulerRegressorQuaternion(QuaternionRatesFromBodyRates(R, w, wd));
    const Eigen::Matrix3d S_w = EulerRegressorOmega(w, wd);
    EXPECT_LT((S_q - S_w).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + S_w.cwiseAbs().maxCoeff()));
  }
}

TEST(PerBodyRegressorTest, OmegaFormIsEulersEquation) {
  // S·diag(J) = J ω̇ + ω × (J ω) for a diagonal J.
  const Eigen::Vector3d w(0.3, -1.2, 0.8), wd(2.0, 0.5, -1.5), J(3.0, 5.0, 7.0);
  const Eigen::Matrix3d I = J.asDiagonal();
  EXPECT_LT((EulerRegressorOmega(w, wd) * J - (I * wd + w.cross(I * w))).norm(), 1e-14);
}

// The per-body equations hold on Bullet's recorded data: max |r| / max |F|
// (Newton) and max |r| / max |N| (Euler) over every step and body.
void ExpectResidualsVanish(const SimulationLog& log, const RobotModel& model) {
  double newton_r = 0, newton_f = 0, euler_r = 0, euler_m = 0;
  for (const LogStep& step : log.steps) {
    for (int i = 0; i < model.n_links(); ++i) {
      const PerBodyRows rows = ComputePerBodyRows(model, i, step);
      const LinkInertia& inertia = model.link(i).inertia;
      newton_r = std::max(newton_r, (inertia.mass * rows.newton_regressor - rows.newton_force).cwiseAbs().maxCoeff());
      newton_f = std::max(newton_f, rows.newton_force.cwiseAbs().maxCoeff());
      euler_r = std::max(euler_r, (rows.euler_regressor * inertia.I_Bcm_B.diagonal() - rows.euler_moment).cwiseAbs().maxCoeff());
      euler_m = std::max(euler_m, rows.euler_moment.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(newton_r / newton_f, 1e-10);
  EXPECT_LT(euler_r / euler_m, 1e-10);
  ::testing::Test::RecordProperty("newton_relative_residual", std::to_string(newton_r / newton_f));
  ::testing::Test::RecordProperty("euler_relative_residual", std::to_string(euler_r / euler_m));
}

TEST(PerBodyRegressorTest, ResidualsOnBulletDataPaperMotion) {
  const RobotModel model = MakePaper6r();
  const auto motion = MakePaperMotion(6, 30.0 * std::numbers::pi / 180.0, 2.0);
  ExpectResidualsVanish(Simulate(model, *motion, SimulationOptions{}), model);
}

TEST(PerBodyRegressorTest, ResidualsOnBulletDataGeneralMotion) {
  const RobotModel model = MakePaper6r();
  const auto motion = MakeGeneralMotion(6, 2.0);
  ExpectResidualsVanish(Simulate(model, *motion, SimulationOptions{}), model);
}

TEST(PerBodyRegressorTest, StockFeedbackBreaksTheEquations) {
  const RobotModel model = MakePaper6r();
  const auto motion = MakeGeneralMotion(6, 2.0);
  SimulationOptions options;
  options.feedback = JointFeedbackMode::kStock;
  const SimulationLog log = Simulate(model, *motion, options);
  double euler_r = 0, euler_m = 0;
  for (const LogStep& step : log.steps) {
    for (int i = 0; i < 6; ++i) {
      const PerBodyRows rows = ComputePerBodyRows(model, i, step);
      euler_r = std::max(euler_r, (rows.euler_regressor * model.link(i).inertia.I_Bcm_B.diagonal() - rows.euler_moment).cwiseAbs().maxCoeff());
      euler_m = std::max(euler_m, rows.euler_moment.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(euler_r / euler_m, 0.1);
}

}  // namespace
}  // namespace idbench
