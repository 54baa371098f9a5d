// tests/data/tx40_like: BIRDy's Stäubli TX40 model (TUM-ICS/BIRDy, TX40.m) as
// a URDF, and FIGAROH's coupled wrist (thanhndv212/figaroh-plus,
// examples/staubli_TX40) as transmission.json. The numbers below are the
// published ones (tests/data/tx40_like/README.md), typed in again here, so a
// change to make_robot.py that moves a frame or an inertia fails.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "engine/test_util.h"
#include "idbench/engine/bullet_simulation.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/kinematics.h"
#include "idbench/engine/urdf.h"
#include "idbench/workbench/formats/transmission_file.h"

namespace idbench {
namespace {

const std::string kDir = std::string(IDBENCH_SOURCE_DIR) + "/tests/data/tx40_like/";

RobotModel LoadTx40() { return LoadUrdfFile(kDir + "tx40_like.urdf").model; }

// BIRDy's modified DH: T_{i-1,i} = RotX(α_i) TransX(a_i) RotZ(θ_i) TransZ(d_i),
// θ = q + (0, -π/2, π/2, 0, 0, π), base 0.32 m above the world.
Eigen::Isometry3d DhPose(const Eigen::VectorXd& q, int link) {
  const double alpha[6] = {0, -M_PI / 2, 0, M_PI / 2, -M_PI / 2, M_PI / 2};
  const double a[6] = {0, 0, 0.225, 0, 0, 0}, d[6] = {0, 0, 0.035, 0.225, 0, 0};
  const double offset[6] = {0, -M_PI / 2, M_PI / 2, 0, 0, M_PI};
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translation().z() = 0.32;
  for (int i = 0; i <= link; ++i) {
    X_WB = X_WB * Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX()) * Eigen::Translation3d(a[i], 0, 0) *
           Eigen::AngleAxisd(q[i] + offset[i], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(0, 0, d[i]);
  }
  return X_WB;
}

TEST(Tx40LikeFixtureTest, LinkFramesAreBirdysDhFrames) {
  const RobotModel model = LoadTx40();
  ASSERT_EQ(model.n_dof(), 6);
  RobotData data(model);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = testing::RandomVector(6, 2.0, &rng), zero = Eigen::VectorXd::Zero(6);
    ComputeKinematics(model, q, zero, zero, &data);
    for (int i = 0; i < 6; ++i) {
      const Eigen::Isometry3d X_WB = DhPose(q, i);
      EXPECT_LT((data.R_WB[static_cast<size_t>(i)] - X_WB.linear()).norm(), 1e-12) << "link " << i + 1;
      EXPECT_LT((data.p_WBo_W[static_cast<size_t>(i)] - X_WB.translation()).norm(), 1e-12) << "link " << i + 1;
    }
  }
}

// BIRDy gives each link's inertia about its DH frame's origin and its first
// moment m·c; the URDF holds the inertia about the centre of mass.
TEST(Tx40LikeFixtureTest, InertialParametersAreBirdys) {
  const RobotModel model = LoadTx40();
  const double mass[6] = {8.61, 4.85, 4.07, 3.62, 1.02, 0.2};
  const double moment[6][3] = {{0, 0, -0.05 * 8.61},       {3.92e-1, -7.2e-3, 1.62e-1}, {3.26e-2, 2.44e-2, 2.65e-1},
                               {1.45e-2, -7.24e-3, -5.86e-1}, {0, -3.06e-3, -1.02e-3},     {0, 0, 8.4e-3}};
  // (XX, XY, XZ, YY, YZ, ZZ) about the DH origin
  const double inertia[6][6] = {{0.424, 0, 0, 0.424, 0, 0.352},
                                {1.63e-2, 7.85e-4, -1.57e-2, 8.81e-2, 3.24e-4, 8.28e-2},
                                {2.23e-2, -1.95e-4, -1.16e-3, 2.24e-2, -2.22e-3, 4.41e-3},
                                {1.09e-1, 2.9e-5, 1.35e-3, 1.08e-1, -1.17e-3, 4.07e-3},
                                {1.01e-3, 0, 0, 1.00e-3, -3.06e-6, 1.01e-3},
                                {3.53e-3, 0, 0, 3.53e-3, 0, 3.53e-4}};
  double total = 0.0;
  for (int i = 0; i < 6; ++i) {
    const LinkInertia& li = model.link(i).inertia;
    total += li.mass;
    EXPECT_DOUBLE_EQ(li.mass, mass[i]) << "link " << i + 1;
    const Eigen::Vector3d mc = li.mass * li.p_BoBcm_B;
    EXPECT_LT((mc - Eigen::Vector3d(moment[i][0], moment[i][1], moment[i][2])).norm(), 1e-11) << "link " << i + 1;
    const Eigen::Vector3d& c = li.p_BoBcm_B;
    const Eigen::Matrix3d I_Bo = li.I_Bcm_B + li.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const double* p = inertia[i];
    Eigen::Matrix3d published;
    published << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
    EXPECT_LT((I_Bo - published).cwiseAbs().maxCoeff(), 1e-11) << "link " << i + 1;
  }
  EXPECT_NEAR(total, 22.37, 1e-12);
  // Joint friction as BIRDy's frictionDatagenModel values.
  const double fv[6] = {7.9379, 5.6948, 1.9804, 1.1141, 1.60, 0.6894};
  const double fc[6] = {6.9822, 7.8301, 6.1939, 2.4063, 3.4092, 1.8313};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(model.link(i).dynamics.viscous, fv[i]);
    EXPECT_EQ(model.link(i).dynamics.coulomb, fc[i]);
  }
}

// FIGAROH's identification.py: θm = red_q·q with red_q = diag(N), red_q[5][4]
// = N6, N = (32, 32, 45, -48, 45, 32): motor 6 turns with joints 5 and 6.
TEST(Tx40LikeFixtureTest, TransmissionIsTheCoupledWrist) {
  const std::optional<Transmission> t = ReadTransmissionArg(kDir + "transmission.json", "", 6, std::nullopt);
  ASSERT_TRUE(t.has_value());
  Eigen::MatrixXd A = Eigen::VectorXd((Eigen::VectorXd(6) << 32, 32, 45, -48, 45, 32).finished()).asDiagonal();
  A(5, 4) = 32;
  EXPECT_EQ(t->actuator_from_joint, A);
  EXPECT_FALSE(t->SingleMotorOf(4).has_value());  // joint 5's column has two motors
  // q6 = θm6/N6 − q5
  Eigen::MatrixXd theta_m(1, 6);
  theta_m << 32 * 0.1, 32 * 0.2, 45 * 0.3, -48 * 0.4, 45 * 0.5, 32 * 0.6;
  const Eigen::MatrixXd q = t->JointPositions(theta_m);
  EXPECT_NEAR(q(0, 4), 0.5, 1e-15);
  EXPECT_NEAR(q(0, 5), 0.6 - 0.5, 1e-15);
}

// The model's inverse dynamics (without the joint friction Bullet lacks)
// are what Bullet realises.
TEST(Tx40LikeFixtureTest, InverseDynamicsEqualBullets) {
  std::vector<Link> links = LoadTx40().links();
  for (Link& link : links) link.dynamics = JointDynamics{};
  const RobotModel model("tx40_like", links);
  BulletSimulation sim(model);
  RobotData data(model);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = testing::RandomVector(6, 2.0, &rng), qd = testing::RandomVector(6, 2.0, &rng),
                          qdd = testing::RandomVector(6, 5.0, &rng);
    Eigen::VectorXd realised;
    sim.Accelerations(q, qd, InverseDynamics(model, q, qd, qdd, &data), 1e-3, &realised, /*feedback=*/false);
    EXPECT_LT(testing::RelativeError(realised, qdd), 1e-9) << "trial " << trial;
  }
}

}  // namespace
}  // namespace idbench
