#include "idbench/excitation/sampled_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "excitation/trajectory_test_util.h"
#include "idbench/excitation/fourier_series.h"

namespace idbench {
namespace {

// A smooth rest-to-rest motion (qdd = 0 at both ends, as the natural spline assumes).
FourierSeriesTrajectory Reference() {
  Eigen::MatrixXd a(2, 3), b(2, 3);
  a << 0.5, -0.2, 0.1, 0.3, 0.4, -0.3;
  b << 0.1, 0.2, -0.4, -0.2, 0.1, 0.05;
  return FourierSeriesTrajectory(Eigen::Vector2d(0.1, -0.3), a, b, 0.2, 5.0, true);
}

// Samples of `reference` every h seconds, from t0 (shifted away by the trajectory).
struct Samples {
  Eigen::VectorXd t;
  Eigen::MatrixXd q, qd, qdd;
};
Samples Sample(const Trajectory& reference, double h, double t0 = 0.0) {
  const int N = static_cast<int>(std::lround(reference.duration() / h)) + 1;
  Samples s{Eigen::VectorXd(N), Eigen::MatrixXd(reference.n_dof(), N), Eigen::MatrixXd(reference.n_dof(), N),
            Eigen::MatrixXd(reference.n_dof(), N)};
  for (int k = 0; k < N; ++k) {
    const JointState x = reference.At(k * h);
    s.t[k] = t0 + k * h;
    s.q.col(k) = x.q;
    s.qd.col(k) = x.qd;
    s.qdd.col(k) = x.qdd;
  }
  return s;
}

// Largest error of q, qd, qdd against the reference on a grid between the samples.
Eigen::Vector3d MaxError(const Trajectory& sampled, const Trajectory& reference) {
  Eigen::Vector3d err = Eigen::Vector3d::Zero();
  for (double t = 0.0; t <= reference.duration(); t += 0.00731) {
    const JointState x = sampled.At(t), y = reference.At(t);
    err = err.cwiseMax(Eigen::Vector3d((x.q - y.q).cwiseAbs().maxCoeff(), (x.qd - y.qd).cwiseAbs().maxCoeff(),
                                       (x.qdd - y.qdd).cwiseAbs().maxCoeff()));
  }
  return err;
}

TEST(SampledTrajectoryTest, QuinticHermitePassesThroughTheSamplesAndTheMotion) {
  const FourierSeriesTrajectory reference = Reference();
  const Samples s = Sample(reference, 0.05, 3.0);
  const SampledTrajectory sampled(s.t, s.q, s.qd, s.qdd);
  EXPECT_EQ(sampled.duration(), 5.0);
  for (int k = 0; k < s.t.size(); ++k) {  // exactly through q, qd, qdd
    const JointState x = sampled.At(s.t[k] - 3.0);
    EXPECT_EQ(x.q, s.q.col(k));
    EXPECT_EQ(x.qd, s.qd.col(k));
    EXPECT_EQ(x.qdd, s.qdd.col(k));
  }
  // Quintic Hermite error: q − p = q⁽⁶⁾(ξ)/6! · τ³(τ − h)³, at most h⁶/(64·720)·|q⁽⁶⁾|;
  // |q⁽⁶⁾| ≤ Σ|a,b| ω_H⁵ ≈ 1.2·3.8⁵ ≈ 950 (plus the quintic's nothing), so q to 2e-10;
  // each derivative loses about a factor 10/h.
  const Eigen::Vector3d err = MaxError(sampled, reference);
  EXPECT_LT(err[0], 2e-10);
  EXPECT_LT(err[1], 4e-8);
  EXPECT_LT(err[2], 8e-6);
  testing::ExpectConsistentDerivatives(sampled);
}

TEST(SampledTrajectoryTest, NaturalCubicSplineFromPositionsAlone) {
  const FourierSeriesTrajectory reference = Reference();
  const Samples s = Sample(reference, 0.01);
  const SampledTrajectory sampled(s.t, s.q);
  for (int k = 0; k < s.t.size(); ++k) EXPECT_EQ(sampled.At(s.t[k]).q, s.q.col(k));  // exactly through q
  // Every interval is a cubic: qdd is linear in between the knots.
  for (int k : {0, 17, 250, 499}) {
    const double mid = 0.5 * (s.t[k] + s.t[k + 1]);
    const Eigen::VectorXd linear = 0.5 * (sampled.qdd().col(k) + sampled.qdd().col(k + 1));
    EXPECT_LT((sampled.At(mid).qdd - linear).cwiseAbs().maxCoeff(), 1e-9) << k;
  }
  EXPECT_EQ(sampled.qdd().col(0).norm(), 0.0);  // natural ends
  // Cubic spline error (Hall & Meyer 1976): q to 5/384 h⁴ |q⁽⁴⁾|, qd to h³/24 |q⁽⁴⁾|,
  // qdd to 3/8 h² |q⁽⁴⁾|; |q⁽⁴⁾| ≤ Σ|a,b| ω_H³ (plus the quintic) ≈ 70 with h = 0.01 s.
  const Eigen::Vector3d err = MaxError(sampled, reference);
  EXPECT_LT(err[0], 1e-8);
  EXPECT_LT(err[1], 3e-6);
  EXPECT_LT(err[2], 3e-3);
  // Away from the knots, where the third derivative jumps.
  testing::ExpectConsistentDerivatives(sampled, 0.1037, 0.3713);
}

TEST(SampledTrajectoryTest, RejectsInconsistentInput) {
  const Eigen::Vector3d t(0, 1, 2);
  EXPECT_THROW(SampledTrajectory(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Zero(2, 1)), std::invalid_argument);
  EXPECT_THROW(SampledTrajectory(t, Eigen::MatrixXd::Zero(2, 4)), std::invalid_argument);
  EXPECT_THROW(SampledTrajectory(Eigen::Vector3d(0, 1, 1), Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
  EXPECT_THROW(SampledTrajectory(t, Eigen::MatrixXd::Zero(2, 3), Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
  try {
    SampledTrajectory(Eigen::Vector3d(0, 2, 1), Eigen::MatrixXd::Zero(2, 3));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t[2] = 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace idbench
