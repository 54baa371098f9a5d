#include "idbench/engine/kinematics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

using testing::RandomVector;

// Along q(t) = q0 + qd t + ½ qdd t², velocities and accelerations from
// ComputeKinematics must match central differences of positions (error
// O(h²) + O(ε/h²) for second differences: h = 1e-4 gives ~1e-7).
TEST(KinematicsTest, DerivativesMatchFiniteDifferences) {
  const RobotModel model = MakePaper6r();
  RobotData d0(model), dp(model), dm(model);
  std::mt19937 rng(7);
  const int n = model.n_dof();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = RandomVector(n, 3.0, &rng), qd = RandomVector(n, 1.5, &rng),
                          qdd = RandomVector(n, 4.0, &rng);
    const double h = 1e-4;
    auto at = [&](double t, RobotData* d) {
      ComputeKinematics(model, q + qd * t + 0.5 * qdd * t * t, qd + qdd * t, qdd, d);
    };
    at(0.0, &d0);
    at(h, &dp);
    at(-h, &dm);
    for (int i = 0; i < n; ++i) {
      const size_t b = static_cast<size_t>(i);
      // Centre-of-mass acceleration from positions.
      const Eigen::Vector3d a_fd = (dp.p_WBcm_W[b] - 2 * d0.p_WBcm_W[b] + dm.p_WBcm_W[b]) / (h * h);
      EXPECT_LT((a_fd - d0.a_WBcm_W[b]).norm(), 1e-5 * (1 + d0.a_WBcm_W[b].norm())) << "link " << i;
      // Hinge-point velocity from positions.
      const Eigen::Vector3d v_fd = (dp.p_WBo_W[b] - dm.p_WBo_W[b]) / (2 * h);
      EXPECT_LT((v_fd - d0.v_WBo_W[b]).norm(), 1e-6 * (1 + d0.v_WBo_W[b].norm()));
      // Angular velocity: [ω]× = Ṙ Rᵀ.
      const Eigen::Matrix3d W = (dp.R_WB[b] - dm.R_WB[b]) / (2 * h) * d0.R_WB[b].transpose();
      EXPECT_LT((Eigen::Vector3d(W(2, 1), W(0, 2), W(1, 0)) - d0.w_WB_W[b]).norm(), 1e-6);
      // Angular acceleration from angular velocities.
      const Eigen::Vector3d wd_fd = (dp.w_WB_W[b] - dm.w_WB_W[b]) / (2 * h);
      EXPECT_LT((wd_fd - d0.wd_WB_W[b]).norm(), 1e-6 * (1 + d0.wd_WB_W[b].norm()));
    }
  }
}

TEST(KinematicsTest, Paper6rInitialPoseMatchesTheDrawing) {
  const RobotModel model = MakePaper6r();
  RobotData d(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(model, zero, zero, zero, &d);
  const Paper6rGeometry g;
  // B1, B2 stacked vertically; B3..B6 along world x at the top of B2.
  EXPECT_LT((d.p_WBo_W[1] - Eigen::Vector3d(0, 0, g.length[0])).norm(), 1e-15);
  const double top = g.length[0] + g.length[1];
  EXPECT_LT((d.p_WBo_W[2] - Eigen::Vector3d(0, 0, top)).norm(), 1e-15);
  EXPECT_LT((d.p_WBcm_W[5] - Eigen::Vector3d(g.length[2] + g.length[3] + g.length[4] + g.length[5] / 2, 0, top))
                .norm(),
            1e-14);
  // Hinge axes: z, y, y, x, y, x.
  const Eigen::Vector3d expected[6] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY(),
                                       Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()};
  for (int i = 0; i < 6; ++i) EXPECT_LT((d.axis_W[static_cast<size_t>(i)] - expected[i]).norm(), 1e-15) << i;
  // Body frames: e2 = world y for all; e1 = z for B1, B2 and x for the rest.
  EXPECT_LT((d.R_WB[0].col(0) - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_LT((d.R_WB[4].col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  for (int i = 0; i < 6; ++i) EXPECT_LT((d.R_WB[static_cast<size_t>(i)].col(1) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

// tests/data/panda_like writes Franka's joint origins as URDF origins (xyz,
// roll); the link frames must be those of Franka's published modified DH
// table (Craig: RotX(alpha) TransX(a) RotZ(q) TransZ(d)), written here from
// the table, at random poses, to 1e-12.
TEST(KinematicsTest, PandaLikeFixtureHasFrankasDhKinematics) {
  const RobotModel model = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/panda_like/panda_like.urdf").model;
  ASSERT_EQ(model.n_dof(), 7);
  const double pi = 3.14159265358979323846;
  const double a[7] = {0, 0, 0, 0.0825, -0.0825, 0, 0.088};
  const double d[7] = {0.333, 0, 0.316, 0, 0.384, 0, 0};
  const double alpha[7] = {0, -pi / 2, pi / 2, pi / 2, -pi / 2, pi / 2, pi / 2};
  std::mt19937 rng(5);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(7);
  KinematicsData<double> k(model);
  for (int pose = 0; pose < 20; ++pose) {
    const Eigen::VectorXd q = RandomVector(7, 2.5, &rng);
    ComputeKinematicsT<double>(model, q, zero, zero, &k);
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 7; ++i) {
      X_WB = X_WB * Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX()) * Eigen::Translation3d(a[i], 0, 0) *
             Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(0, 0, d[i]);
      EXPECT_LT((k.p_WBo_W[static_cast<size_t>(i)] - X_WB.translation()).norm(), 1e-12) << "link " << i + 1;
      EXPECT_LT((k.R_WB[static_cast<size_t>(i)] - X_WB.linear()).norm(), 1e-12) << "link " << i + 1;
    }
  }
}

TEST(KinematicsTest, RejectsWrongSizes) {
  const RobotModel model = MakePaper6r();
  RobotData d(model);
  EXPECT_THROW(ComputeKinematics(model, Eigen::VectorXd::Zero(5), Eigen::VectorXd::Zero(6),
                                 Eigen::VectorXd::Zero(6), &d),
               std::invalid_argument);
}

}  // namespace
}  // namespace idbench
