#include "idbench/engine/quaternion.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "engine/test_util.h"

namespace idbench {
namespace {

using testing::RandomVector;

Eigen::Matrix3d RandomRotation(std::mt19937* rng) {
  const Eigen::Vector3d axis = RandomVector(3, 1.0, rng).normalized();
  return Eigen::AngleAxisd(RandomVector(1, 3.0, rng)[0], axis).toRotationMatrix();
}

TEST(QuaternionTest, RoundTripThroughRotation) {
  std::mt19937 rng(1);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Matrix3d R = RandomRotation(&rng);
    const Quaternion4 lambda = QuaternionFromRotation(R);
    EXPECT_NEAR(lambda.norm(), 1.0, 1e-15);
    EXPECT_GE(lambda[0], 0.0);
    EXPECT_LT((RotationFromQuaternion(lambda) - R).norm(), 1e-14);
  }
}

TEST(QuaternionTest, RatesSatisfyThePapersIdentities) {
  std::mt19937 rng(2);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d w_B = RandomVector(3, 2.0, &rng), wd_B = RandomVector(3, 5.0, &rng);
    const QuaternionRates r = QuaternionRatesFromBodyRates(RandomRotation(&rng), w_B, wd_B);
    const Eigen::Matrix<double, 3, 4> L = QuaternionL(r.lambda);
    EXPECT_LT((2.0 * L * r.lambda_d - w_B).norm(), 1e-14);   // ω = 2 L Λ'
    EXPECT_LT((2.0 * L * r.lambda_dd - wd_B).norm(), 1e-14); // ω̇ = 2 L Λ''
    EXPECT_NEAR(r.lambda.dot(r.lambda_d), 0.0, 1e-15);        // Λᵀ Λ' = 0
    EXPECT_NEAR(r.lambda.dot(r.lambda_dd) + r.lambda_d.dot(r.lambda_d), 0.0, 1e-14);
    EXPECT_LT((QuaternionL(r.lambda_d) * r.lambda_d).norm(), 1e-15);  // L(Λ') Λ' = 0
  }
}

TEST(QuaternionTest, RateMatchesFiniteDifferenceOfOrientation) {
  // R(t) = R0 · exp([ω]× t) has constant body rate ω; Λ' = dΛ/dt.
  std::mt19937 rng(3);
  const Eigen::Matrix3d R0 = RandomRotation(&rng);
  const Eigen::Vector3d w_B(0.3, -0.7, 1.1);
  auto lambda_at = [&](double t) {
    return QuaternionFromRotation(R0 * Eigen::AngleAxisd(w_B.norm() * t, w_B.normalized()).toRotationMatrix());
  };
  const double h = 1e-5;
  const Quaternion4 fd = (lambda_at(h) - lambda_at(-h)) / (2 * h);
  const QuaternionRates r = QuaternionRatesFromBodyRates(R0, w_B, Eigen::Vector3d::Zero());
  // Central difference: error O(h²‖Λ'''‖) + O(ε/h) ≈ 1e-10.
  EXPECT_LT((fd - r.lambda_d).norm(), 1e-9);
}

}  // namespace
}  // namespace idbench
