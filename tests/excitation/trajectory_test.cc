#include <gtest/gtest.h>

#include "idbench/excitation/builtin_motions.h"
#include "idbench/excitation/constant_acceleration.h"
#include "idbench/excitation/fourier_series.h"
#include "excitation/trajectory_test_util.h"

namespace idbench {
namespace {

using testing::ExpectConsistentDerivatives;

TEST(TrajectoryTest, FourierSeriesDerivativesAndPeriod) {
  Eigen::MatrixXd a(2, 3), b(2, 3);
  a << 0.5, -0.2, 0.1, 0.3, 0.4, -0.3;
  b << 0.1, 0.2, -0.4, -0.2, 0.1, 0.05;
  const FourierSeriesTrajectory traj(Eigen::Vector2d(0.1, -0.3), a, b, 0.2, 10.0);
  ExpectConsistentDerivatives(traj);
  const JointState s0 = traj.At(0.3), s1 = traj.At(0.3 + 5.0);  // period 1/f0 = 5 s
  EXPECT_LT((s0.q - s1.q).norm(), 1e-13);
  EXPECT_LT((s0.qdd - s1.qdd).norm(), 1e-12);
}

TEST(TrajectoryTest, ConstantAccelerationIsAParabola) {
  const ConstantAccelerationTrajectory traj(Eigen::Vector2d(1, 2), Eigen::Vector2d(0.5, 0), Eigen::Vector2d(2, -1), 3);
  ExpectConsistentDerivatives(traj);
  const JointState s = traj.At(2.0);
  EXPECT_DOUBLE_EQ(s.q[0], 1 + 0.5 * 2 + 0.5 * 2 * 4);
  EXPECT_DOUBLE_EQ(s.qd[1], -2.0);
}

TEST(TrajectoryTest, BuiltinMotions) {
  const auto paper = MakePaperMotion(6, 0.5, 2.0);
  const JointState s = paper->At(1.0);
  EXPECT_DOUBLE_EQ(s.qdd[0], 0.5);
  EXPECT_DOUBLE_EQ(s.qdd[1], 0.5);
  EXPECT_EQ(s.qdd.tail(4).norm(), 0.0);
  const auto general = MakeGeneralMotion(6, 4.0);
  ExpectConsistentDerivatives(*general);
  EXPECT_LT(general->At(0.0).q.norm(), 1e-15);  // starts at the initial pose
  EXPECT_GT(general->At(1.0).qd.cwiseAbs().minCoeff(), 0.0);  // every joint moves
}

TEST(TrajectoryTest, ReversedMotionRetracesTheForwardOne) {
  const auto forward = MakeBuiltinMotion("general", 6, 4.0, 0.0);
  const auto reversed = MakeBuiltinMotion("general-reversed", 6, 4.0, 0.0);
  ExpectConsistentDerivatives(*reversed);
  for (double t : {0.0, 0.7, 2.5, 4.0}) {
    const JointState f = forward->At(4.0 - t), r = reversed->At(t);
    EXPECT_LT((r.q - f.q).norm(), 1e-15);
    EXPECT_LT((r.qd + f.qd).norm(), 1e-15);
    EXPECT_LT((r.qdd - f.qdd).norm(), 1e-15);
  }
  EXPECT_THROW(MakeBuiltinMotion("sideways", 6, 4.0, 0.0), std::invalid_argument);
}

TEST(TrajectoryTest, RejectsInconsistentInput) {
  EXPECT_THROW(FourierSeriesTrajectory(Eigen::Vector2d(0, 0), Eigen::MatrixXd(3, 2), Eigen::MatrixXd(3, 2), 0.1, 1),
               std::invalid_argument);
  EXPECT_THROW(FourierSeriesTrajectory(Eigen::Vector2d(0, 0), Eigen::MatrixXd::Zero(2, 2), Eigen::MatrixXd::Zero(2, 2), 0.0, 1),
               std::invalid_argument);
  EXPECT_THROW(ConstantAccelerationTrajectory(Eigen::Vector2d(0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector2d(0, 0), 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace idbench
