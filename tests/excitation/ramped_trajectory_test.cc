#include "idbench/excitation/ramped_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "idbench/excitation/constant_acceleration.h"
#include "idbench/excitation/fourier_series.h"

namespace idbench {
namespace {

std::shared_ptr<const Trajectory> TwoJointFourier() {
  Eigen::MatrixXd a(2, 2), b(2, 2);
  a << 0.3, -0.2, 0.1, 0.25;
  b << -0.15, 0.05, 0.2, -0.1;
  return std::make_shared<FourierSeriesTrajectory>(Eigen::Vector2d(0.4, -0.7), a, b, 0.2, 5.0, false);
}

void ExpectState(const JointState& got, const JointState& want, double tol) {
  EXPECT_LE((got.q - want.q).norm(), tol) << got.q.transpose() << " vs " << want.q.transpose();
  EXPECT_LE((got.qd - want.qd).norm(), tol) << got.qd.transpose() << " vs " << want.qd.transpose();
  EXPECT_LE((got.qdd - want.qdd).norm(), tol) << got.qdd.transpose() << " vs " << want.qdd.transpose();
}

// Starts and ends at home at rest; continuous in q, qd, qdd where the ramps
// meet the motion; the motion in between shifted by the ramp.
TEST(RampedTrajectoryTest, RestAtHomeAtBothEndsAndContinuousAtTheJoins) {
  const auto motion = TwoJointFourier();
  const Eigen::Vector2d home(0.1, -0.2);
  const RampedTrajectory ramped(motion, home, 1.5);
  EXPECT_DOUBLE_EQ(ramped.duration(), 5.0 + 3.0);
  JointState rest(2);
  rest.q = home;
  ExpectState(ramped.At(0.0), rest, 1e-15);
  ExpectState(ramped.At(8.0), rest, 1e-12);
  // Each side of the joins: the ramp's formula just before, the motion's just after.
  const double eps = 1e-9;
  ExpectState(ramped.At(1.5 - eps), motion->At(0.0), 1e-7);
  ExpectState(ramped.At(6.5 + eps), motion->At(5.0), 1e-7);
  // In the ramps each joint lies between the home and the periodic motion continued.
  for (double t : {0.3, 0.9, 6.8, 7.7}) {
    const Eigen::VectorXd q = ramped.At(t).q, m = motion->At(t - 1.5).q;
    for (int j = 0; j < 2; ++j) {
      EXPECT_GE(q[j], std::min(home[j], m[j]) - 1e-15) << t;
      EXPECT_LE(q[j], std::max(home[j], m[j]) + 1e-15) << t;
    }
  }
  ExpectState(ramped.At(1.5 + 2.0), motion->At(2.0), 0.0);
}

// qd and qdd of the ramps are the derivatives of q (central differences,
// error O(h²) ≈ 1e-6 · |q'''|, rounding ε/h ≈ 1e-11).
TEST(RampedTrajectoryTest, RampDerivativesMatchCentralDifferences) {
  const RampedTrajectory ramped(TwoJointFourier(), Eigen::Vector2d(0.1, -0.2), 1.5);
  const double h = 1e-4;
  for (double t : {0.2, 0.7, 1.3, 6.6, 7.1, 7.9}) {
    const JointState s = ramped.At(t), plus = ramped.At(t + h), minus = ramped.At(t - h);
    EXPECT_LT(((plus.q - minus.q) / (2 * h) - s.qd).norm(), 1e-6) << "t = " << t;
    EXPECT_LT(((plus.qd - minus.qd) / (2 * h) - s.qdd).norm(), 1e-6) << "t = " << t;
  }
}

// A motion at rest at its ends: the ramps are from rest to rest over Δ in
// T, peaks 10/√3·Δ/T² and 15/8·Δ/T (the quintic 10s³ − 15s⁴ + 6s⁵), found on
// a 0.1 ms grid.
TEST(RampedTrajectoryTest, RestToRestPeaksAreTheQuintics) {
  const Eigen::Vector2d pose(0.5, -1.0), home(0.0, 0.2);
  auto still = std::make_shared<ConstantAccelerationTrajectory>(pose, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), 1.0);
  const double T = 0.8;
  const RampedTrajectory ramped(still, home, T);
  Eigen::Vector2d qd_peak = Eigen::Vector2d::Zero(), qdd_peak = Eigen::Vector2d::Zero();
  for (double t = 0.0; t <= T; t += 1e-4) {
    const JointState s = ramped.At(t);
    qd_peak = qd_peak.cwiseMax(s.qd.cwiseAbs());
    qdd_peak = qdd_peak.cwiseMax(s.qdd.cwiseAbs());
  }
  const Eigen::Vector2d delta = (pose - home).cwiseAbs();
  EXPECT_LT((qd_peak - 15.0 / 8.0 * delta / T).norm(), 1e-6);
  EXPECT_LT((qdd_peak - 10.0 / std::sqrt(3.0) * delta / (T * T)).norm(), 1e-4);
}

TEST(RampedTrajectoryTest, NoRampIsTheMotionAndBadArgumentsThrow) {
  const auto motion = TwoJointFourier();
  const RampedTrajectory plain(motion, Eigen::Vector2d::Zero(), 0.0);
  EXPECT_EQ(plain.duration(), motion->duration());
  for (double t : {0.0, 1.3, 5.0}) ExpectState(plain.At(t), motion->At(t), 0.0);
  EXPECT_THROW(RampedTrajectory(motion, Eigen::Vector3d::Zero(), 1.0), std::invalid_argument);
  EXPECT_THROW(RampedTrajectory(motion, Eigen::Vector2d::Zero(), -1.0), std::invalid_argument);
  EXPECT_THROW(RampedTrajectory(motion, Eigen::Vector2d::Zero(), NAN), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
