#include "idbench/excitation/fourier_series.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "excitation/trajectory_test_util.h"

namespace idbench {
namespace {

using testing::ExpectConsistentDerivatives;

constexpr double kF0 = 0.2;        // [Hz]: period 5 s
constexpr double kDuration = 7.3;  // [s]: not a whole number of periods, so f(T) ≠ f(0)

FourierSeriesTrajectory MakeSeries(bool rest_to_rest) {
  Eigen::MatrixXd a(3, 3), b(3, 3);
  a << 0.5, -0.2, 0.1, 0.3, 0.4, -0.3, -0.6, 0.05, 0.2;
  b << 0.1, 0.2, -0.4, -0.2, 0.1, 0.05, 0.3, -0.25, 0.15;
  return FourierSeriesTrajectory(Eigen::Vector3d(0.1, -0.3, 0.7), a, b, kF0, kDuration, rest_to_rest);
}

// The series written out term by term (the header's formula).
JointState PlainSeries(const FourierSeriesTrajectory& s, double t) {
  JointState x(s.n_dof());
  x.q = s.q0();
  for (int j = 0; j < s.n_dof(); ++j) {
    for (int l = 1; l <= s.harmonics(); ++l) {
      const double w = 2 * std::numbers::pi * s.f0() * l;
      const double a = s.a()(j, l - 1), b = s.b()(j, l - 1);
      x.q[j] += a / w * std::sin(w * t) - b / w * std::cos(w * t);
      x.qd[j] += a * std::cos(w * t) + b * std::sin(w * t);
      x.qdd[j] += -a * w * std::sin(w * t) + b * w * std::cos(w * t);
    }
  }
  return x;
}

double RelativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& truth) {
  return (x - truth).norm() / truth.norm();
}

TEST(FourierSeriesTest, PlainSeriesMatchesTheFormula) {
  const FourierSeriesTrajectory s = MakeSeries(false);
  EXPECT_FALSE(s.rest_to_rest());
  for (double t : {0.0, 0.37, 2.5, 7.3}) {
    const JointState x = s.At(t), truth = PlainSeries(s, t);
    EXPECT_LT(RelativeError(x.q, truth.q), 1e-15) << t;
    EXPECT_LT(RelativeError(x.qd, truth.qd), 1e-15) << t;
    EXPECT_LT(RelativeError(x.qdd, truth.qdd), 1e-15) << t;
  }
}

TEST(FourierSeriesTest, RestToRestStartsAndEndsAtRestAtTheStartPose) {
  const FourierSeriesTrajectory s = MakeSeries(true);
  EXPECT_TRUE(s.rest_to_rest());
  const JointState start = s.At(0.0), end = s.At(kDuration);
  EXPECT_LE(start.qd.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(start.qdd.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(end.qd.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(end.qdd.cwiseAbs().maxCoeff(), 1e-12);
  // q(0) = q(T) = q0 + f(0) = q0 − Σ_l b_l/(ω_f l).
  const JointState plain_start = PlainSeries(s, 0.0);
  EXPECT_LT(RelativeError(start.q, plain_start.q), 1e-15);
  EXPECT_LT(RelativeError(end.q, plain_start.q), 1e-14);
  ExpectConsistentDerivatives(s);
}

// The rest-to-rest motion minus the plain one is the quintic fixed by the six
// end conditions, here found independently from the 6×6 system of the
// monomials' values and derivatives at 0 and T.
TEST(FourierSeriesTest, RestToRestAddsTheQuinticOfTheEndConditions) {
  const FourierSeriesTrajectory rest = MakeSeries(true), plain = MakeSeries(false);
  const double T = kDuration;
  Eigen::Matrix<double, 6, 6> A;  // rows: p(0), p'(0), p''(0), p(T), p'(T), p''(T) of 1, t, …, t⁵
  for (int k = 0; k < 6; ++k) {
    A(0, k) = k == 0 ? 1 : 0;
    A(1, k) = k == 1 ? 1 : 0;
    A(2, k) = k == 2 ? 2 : 0;
    A(3, k) = std::pow(T, k);
    A(4, k) = k >= 1 ? k * std::pow(T, k - 1) : 0;
    A(5, k) = k >= 2 ? k * (k - 1) * std::pow(T, k - 2) : 0;
  }
  const JointState f0 = PlainSeries(plain, 0.0), fT = PlainSeries(plain, T);
  for (int j = 0; j < rest.n_dof(); ++j) {
    Eigen::Matrix<double, 6, 1> ends;
    ends << 0, -f0.qd[j], -f0.qdd[j], f0.q[j] - fT.q[j], -fT.qd[j], -fT.qdd[j];
    const Eigen::Matrix<double, 6, 1> c = A.fullPivLu().solve(ends);
    for (double t : {0.4, 1.9, 3.65, 6.1}) {
      double p = 0, dp = 0, ddp = 0;
      for (int k = 0; k < 6; ++k) {
        p += c[k] * std::pow(t, k);
        if (k >= 1) dp += c[k] * k * std::pow(t, k - 1);
        if (k >= 2) ddp += c[k] * k * (k - 1) * std::pow(t, k - 2);
      }
      const JointState x = rest.At(t), y = PlainSeries(plain, t);
      // Tolerance: the monomial solve loses cond(A)·ε ≈ 1e-11 relative.
      EXPECT_NEAR(x.q[j], y.q[j] + p, 1e-10) << "joint " << j << ", t = " << t;
      EXPECT_NEAR(x.qd[j], y.qd[j] + dp, 1e-10) << "joint " << j << ", t = " << t;
      EXPECT_NEAR(x.qdd[j], y.qdd[j] + ddp, 1e-10) << "joint " << j << ", t = " << t;
    }
  }
}

// q = q0 + [a b]·w.q (and likewise qd, qdd) with the weights the design uses.
TEST(FourierSeriesTest, BasisTimesCoefficientsIsTheMotion) {
  for (bool rest_to_rest : {false, true}) {
    const FourierSeriesTrajectory s = MakeSeries(rest_to_rest);
    const int H = s.harmonics();
    FourierBasis reused;
    for (double t : {0.0, 1.1, 4.2, kDuration}) {
      const FourierBasis w = FourierSeriesTrajectory::BasisAt(t, kF0, H, kDuration, rest_to_rest);
      FourierSeriesTrajectory::BasisAt(t, kF0, H, kDuration, rest_to_rest, &reused);
      ASSERT_EQ(w.q.size(), 2 * H);
      EXPECT_EQ(w.qdd, reused.qdd);
      const JointState x = s.At(t);
      for (int j = 0; j < s.n_dof(); ++j) {
        Eigen::VectorXd coefficients(2 * H);
        coefficients << s.a().row(j).transpose(), s.b().row(j).transpose();
        EXPECT_NEAR(s.q0()[j] + w.q.dot(coefficients), x.q[j], 1e-15 * (1 + std::abs(x.q[j])));
        EXPECT_NEAR(w.qd.dot(coefficients), x.qd[j], 1e-15 * (1 + std::abs(x.qd[j])));
        EXPECT_NEAR(w.qdd.dot(coefficients), x.qdd[j], 1e-15 * (1 + std::abs(x.qdd[j])));
      }
    }
  }
}

}  // namespace
}  // namespace idbench
