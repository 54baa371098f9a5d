#include "idbench/ident/payload_estimator.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <random>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/single_joint_motion.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

using Vector10 = Eigen::Matrix<double, 10, 1>;

// The puma560 along the general motion (10 s at 100 Hz), unloaded and with a
// 2.5 kg payload off-centre on the last link, noise-free torques.
struct PayloadExperiment {
  RobotModel model = MakePuma560();
  PayloadBody truth;
  TorqueLog unloaded, loaded;

  PayloadExperiment() {
    truth.mass = 2.5;
    truth.p_BoPcm_B = {0.02, -0.03, 0.08};
    truth.I_Pcm_B << 0.02, 1e-3, -5e-4, 0.025, 1.5e-3, 0.015;  // Ixx, Ixy, Ixz, Iyy, Iyz, Izz
    const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
    const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
    unloaded.motion = testing::SyntheticJointLog(model, *motion, t);
    loaded.motion = testing::SyntheticJointLog(Loaded(model), *motion, t);
  }
  RobotModel Loaded(const RobotModel& robot) const {
    return testing::WithPayload(robot, truth.mass, truth.p_BoPcm_B, TruthInertia());
  }
  Eigen::Matrix3d TruthInertia() const {
    const auto& I = truth.I_Pcm_B;
    return (Eigen::Matrix3d() << I[0], I[1], I[2], I[1], I[3], I[4], I[2], I[4], I[5]).finished();
  }
  Vector10 TruthQuantities() const { return PayloadQuantities(truth); }
};

// The 10 quantities' error relative to the truth's scale per group (mass,
// COM, inertia), so that a small entry is not judged against itself.
double QuantityError(const Vector10& estimate, const Vector10& truth) {
  return std::max({std::abs(estimate[0] - truth[0]) / truth[0],
                   testing::RelativeError(estimate.segment<3>(1), truth.segment<3>(1)),
                   testing::RelativeError(estimate.tail<6>(), truth.tail<6>())});
}

TEST(PayloadEstimatorTest, BodyAndParametersAreInverse) {
  const PayloadExperiment e;
  const InertialParameters phi = PayloadParametersFromBody(e.truth);
  EXPECT_LT(QuantityError(PayloadQuantities(PayloadBodyFromParameters(phi)), e.TruthQuantities()), 1e-14);
  // The Jacobian against central differences (error h², h = 1e-6 relative).
  const Eigen::Matrix<double, 10, 10> J = PayloadQuantityJacobian(phi);
  for (int i = 0; i < 10; ++i) {
    const double h = 1e-6 * std::max(1e-2, std::abs(phi[i]));
    InertialParameters up = phi, down = phi;
    up[i] += h, down[i] -= h;
    const Vector10 fd = (PayloadQuantities(PayloadBodyFromParameters(up)) -
                         PayloadQuantities(PayloadBodyFromParameters(down))) / (2 * h);
    EXPECT_LT((fd - J.col(i)).norm(), 1e-6 * std::max(1.0, J.col(i).norm())) << i;
  }
}

// Noise-free: one log (the robot file subtracted) and two logs recover the
// payload to 1e-6, consistent as it is.
TEST(PayloadEstimatorTest, NoiseFreeLogsRecoverThePayload) {
  const PayloadExperiment e;
  for (const TorqueLog* unloaded : {static_cast<const TorqueLog*>(nullptr), &e.unloaded}) {
    const PayloadEstimate estimate = EstimatePayload(e.model, e.loaded, unloaded, {});
    ASSERT_EQ(estimate.status, PayloadStatus::kEstimated) << estimate.message;
    const double error = QuantityError(PayloadQuantities(estimate.body), e.TruthQuantities());
    std::printf("%s log(s), noise-free: quantity error %.3g, rank %d\n", unloaded ? "two" : "one", error, estimate.rank);
    EXPECT_LT(error, 1e-6);
    EXPECT_LT(testing::RelativeError(estimate.phi, PayloadParametersFromBody(e.truth)), 1e-6);
    EXPECT_EQ(estimate.projection_distance, 0.0);
    EXPECT_EQ(estimate.link, 5);
  }
}

// Torque noise σ 0.02 N m on every joint: over 100 seeds (1..100) the
// spread of each quantity agrees with the σ the estimator reports (the mean
// over seeds) within 20 %, for one log and for two. The noise leaves every
// least-squares estimate a physical body (projection distance 0), so the
// spread is the least-squares one that σ describes.
TEST(PayloadEstimatorTest, SigmaAgreesWithMonteCarloSpread) {
  const PayloadExperiment e;
  constexpr int kSeeds = 100;
  constexpr double kNoise = 0.02;  // [N m]
  for (const bool two_logs : {false, true}) {
    Eigen::MatrixXd estimates(kSeeds, 10);
    Vector10 mean_sigma = Vector10::Zero();
    for (int seed = 1; seed <= kSeeds; ++seed) {
      std::mt19937 rng(static_cast<unsigned>(seed));
      std::normal_distribution<double> normal(0.0, kNoise);
      TorqueLog loaded = e.loaded, unloaded = e.unloaded;
      for (TorqueLog* log : {&loaded, &unloaded}) log->motion.tau = log->motion.tau.unaryExpr([&](double x) {
        return x + normal(rng);
      });
      const PayloadEstimate estimate = EstimatePayload(e.model, loaded, two_logs ? &unloaded : nullptr, {});
      ASSERT_EQ(estimate.status, PayloadStatus::kEstimated) << estimate.message;
      ASSERT_EQ(estimate.projection_distance, 0.0) << seed;
      estimates.row(seed - 1) = PayloadQuantities(estimate.body).transpose();
      mean_sigma += estimate.sigma / kSeeds;
    }
    const Eigen::RowVectorXd mean = estimates.colwise().mean();
    const Eigen::RowVectorXd spread =
        ((estimates.rowwise() - mean).colwise().squaredNorm() / (kSeeds - 1)).cwiseSqrt();
    for (int k = 0; k < 10; ++k) {
      const double ratio = mean_sigma[k] / spread[k];
      std::printf("%s: %-5s sigma %.3g, MC spread %.3g (ratio %.3f), bias %.2g sigma\n", two_logs ? "two logs" : "one log",
                  PayloadQuantityNames()[k].c_str(), mean_sigma[k], spread[k], ratio,
                  (mean[k] - e.TruthQuantities()[k]) / spread[k]);
      EXPECT_NEAR(ratio, 1.0, 0.2) << PayloadQuantityNames()[k];
    }
  }
}

// Torque noise coloured as a robot's sensing is (AR(1), ρ = 0.9 per joint,
// stationary σ 0.02 N m, drawn here independently of the library): over 100
// seeds the spread of each quantity agrees with the batch-means σ within
// 30 % (σ from ~30 blocks scatters more than the white formula's), where
// the white-residual σ, sigma_white, is short by about the AR(1) factor
// √((1 − ρ)/(1 + ρ)) = 0.23 (below 0.5 for every quantity).
TEST(PayloadEstimatorTest, ColouredNoiseSigmaAgreesWithMonteCarloSpread) {
  const PayloadExperiment e;
  constexpr int kSeeds = 100;
  constexpr double kNoise = 0.02, kRho = 0.9;  // [N m], lag-1 correlation
  for (const bool two_logs : {false, true}) {
    Eigen::MatrixXd estimates(kSeeds, 10);
    Vector10 mean_sigma = Vector10::Zero(), mean_white = Vector10::Zero();
    for (int seed = 1; seed <= kSeeds; ++seed) {
      std::mt19937 rng(static_cast<unsigned>(seed));
      std::normal_distribution<double> normal(0.0, 1.0);
      TorqueLog loaded = e.loaded, unloaded = e.unloaded;
      for (TorqueLog* log : {&loaded, &unloaded}) {
        Eigen::MatrixXd& tau = log->motion.tau;
        for (Eigen::Index j = 0; j < tau.cols(); ++j) {
          double x = kNoise * normal(rng);
          for (Eigen::Index s = 0; s < tau.rows(); ++s) {
            if (s > 0) x = kRho * x + kNoise * std::sqrt(1.0 - kRho * kRho) * normal(rng);
            tau(s, j) += x;
          }
        }
      }
      const PayloadEstimate estimate = EstimatePayload(e.model, loaded, two_logs ? &unloaded : nullptr, {});
      ASSERT_NE(estimate.status, PayloadStatus::kNotIdentifiable) << estimate.message;
      EXPECT_EQ(estimate.covariance_method.method, CovarianceMethod::kBatchMeans);
      estimates.row(seed - 1) = PayloadQuantities(estimate.body).transpose();
      mean_sigma += estimate.sigma / kSeeds;
      mean_white += estimate.sigma_white / kSeeds;
    }
    const Eigen::RowVectorXd mean = estimates.colwise().mean();
    const Eigen::RowVectorXd spread =
        ((estimates.rowwise() - mean).colwise().squaredNorm() / (kSeeds - 1)).cwiseSqrt();
    for (int k = 0; k < 10; ++k) {
      const double ratio = mean_sigma[k] / spread[k], white = mean_white[k] / spread[k];
      std::printf("%s, AR(1) 0.9: %-5s sigma/spread %.3f, white %.3f\n", two_logs ? "two logs" : "one log",
                  PayloadQuantityNames()[k].c_str(), ratio, white);
      EXPECT_NEAR(ratio, 1.0, 0.3) << PayloadQuantityNames()[k];
      EXPECT_LT(white, 0.5) << PayloadQuantityNames()[k];
    }
  }
}

// A robot file with link 3's mass 10 % off: one log, which subtracts the
// file's model, is biased; the unloaded log of the same motion cancels it.
TEST(PayloadEstimatorTest, UnloadedLogCancelsAWrongRobotModel) {
  const PayloadExperiment e;
  std::vector<Link> links = e.model.links();
  links[2].inertia.mass *= 1.1;
  const RobotModel wrong("puma560 (link 3 mass +10 %)", links, e.model.gravity_W());
  const PayloadEstimate one = EstimatePayload(wrong, e.loaded, nullptr, {});
  const PayloadEstimate two = EstimatePayload(wrong, e.loaded, &e.unloaded, {});
  ASSERT_EQ(two.status, PayloadStatus::kEstimated) << two.message;
  const double one_error = QuantityError(PayloadQuantities(one.body), e.TruthQuantities());
  const double two_error = QuantityError(PayloadQuantities(two.body), e.TruthQuantities());
  std::printf("wrong robot file: one log error %.3g (mass %.4g kg, status %s), two logs %.3g\n", one_error,
              one.body.mass, PayloadStatusName(one.status), two_error);
  EXPECT_GT(std::abs(one.body.mass - e.truth.mass) / e.truth.mass, 0.05);
  EXPECT_LT(two_error, 1e-6);
}

// Only the last joint turns (the others held at a pose): the payload turns
// about its link's z axis only, so the inertia terms Ixx, Ixy, Iyy (about
// the link origin, hence about the COM) are not seen; the rest is, and the
// estimate says so by name instead of giving numbers.
TEST(PayloadEstimatorTest, MotionOfOneJointReportsTheUnseenTerms) {
  const PayloadExperiment e;
  ASSERT_TRUE(e.model.links().back().axis_J.isApprox(Eigen::Vector3d::UnitZ()));
  const testing::SingleJointMotion motion((Eigen::VectorXd(6) << 0.3, -0.6, 0.4, 0.5, 0.7, 0.0).finished(), 5, 10.0);
  TorqueLog loaded;
  loaded.motion = testing::SyntheticJointLog(e.Loaded(e.model), motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
  const PayloadEstimate estimate = EstimatePayload(e.model, loaded, nullptr, {});
  EXPECT_EQ(estimate.status, PayloadStatus::kNotIdentifiable);
  std::printf("joint 6 only: %s\n", estimate.message.c_str());
  const std::vector<std::string> unseen{"Ixx", "Ixy", "Iyy"};
  const Vector10 truth = e.TruthQuantities(), got = PayloadQuantities(estimate.body);
  for (int k = 0; k < 10; ++k) {
    const std::string& name = PayloadQuantityNames()[k];
    const bool expected_unseen = std::find(unseen.begin(), unseen.end(), name) != unseen.end();
    EXPECT_EQ(estimate.identifiable[k], !expected_unseen) << name;
    if (expected_unseen) {
      EXPECT_TRUE(std::isnan(got[k])) << name;
      EXPECT_TRUE(std::isnan(estimate.sigma[k])) << name;
      EXPECT_NE(estimate.not_identifiable_reason[k].find("Bo"), std::string::npos) << estimate.not_identifiable_reason[k];
      EXPECT_NE(estimate.message.find(name), std::string::npos) << estimate.message;
    } else {
      EXPECT_NEAR(got[k], truth[k], 1e-6 * (k == 0 ? truth[0] : k < 4 ? 0.08 : 0.025)) << name;
    }
  }
}

// A thin rod (Izz about its axis 10⁻⁵ kg m²) with torque noise 0.05 N m: the
// least-squares inertia often is no body's; the consistent estimate is one
// (pseudo-inertia ⪰ 0), and, being the nearest body in the covariance's
// metric, no farther from the least-squares one than the truth (a body) is.
TEST(PayloadEstimatorTest, ConsistentEstimateIsTheNearestBody) {
  PayloadExperiment e;
  e.truth.I_Pcm_B << 0.01, 0.0, 0.0, 0.01, 0.0, 1e-5;
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  e.loaded.motion = testing::SyntheticJointLog(e.Loaded(e.model), *motion, e.loaded.motion.t);
  const InertialParameters phi_true = PayloadParametersFromBody(e.truth);
  int projected = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 0.05);
    TorqueLog loaded = e.loaded;
    loaded.motion.tau = loaded.motion.tau.unaryExpr([&](double x) { return x + normal(rng); });
    const PayloadEstimate estimate = EstimatePayload(e.model, loaded, nullptr, {});
    const double min_eigenvalue =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(PseudoInertia(estimate.consistent_phi)).eigenvalues().minCoeff();
    EXPECT_GE(min_eigenvalue, 0.0) << seed;
    if (estimate.projection_distance == 0.0) {
      EXPECT_GE(estimate.min_pseudo_inertia_eigenvalue, 0.0);
      continue;
    }
    ++projected;
    EXPECT_LT(estimate.min_pseudo_inertia_eigenvalue, 0.0);
    const InertialParameters d = phi_true - estimate.phi;
    const double truth_distance = std::sqrt(d.dot(estimate.covariance.ldlt().solve(d)));
    EXPECT_LE(estimate.projection_distance, truth_distance * (1 + 1e-6)) << seed;
    if (projected == 1) {
      std::printf("seed %u: least-squares pseudo-inertia eigenvalue %.3g; consistent one %.3g, %.3g sigma away (truth "
                  "%.3g sigma)\n", seed, estimate.min_pseudo_inertia_eigenvalue, min_eigenvalue,
                  estimate.projection_distance, truth_distance);
    }
  }
  std::printf("projected in %d of 20 seeds\n", projected);
  EXPECT_GT(projected, 0);
}

// Torque noise 1 N m: the mass and COM stay determined, the inertia's σ is
// larger than a tenth of its scale (tr I/2): poorly determined, naming it.
TEST(PayloadEstimatorTest, NoisyInertiaIsPoorlyDetermined) {
  PayloadExperiment e;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  e.loaded.motion.tau = e.loaded.motion.tau.unaryExpr([&](double x) { return x + normal(rng); });
  const PayloadEstimate estimate = EstimatePayload(e.model, e.loaded, nullptr, {});
  std::printf("1 N m noise: %s\n", estimate.message.c_str());
  EXPECT_EQ(estimate.status, PayloadStatus::kPoorlyDetermined);
  EXPECT_NE(estimate.message.find("payload's I"), std::string::npos) << estimate.message;
  EXPECT_LT(estimate.sigma[0], 0.1 * e.truth.mass);
  const double half_trace = 0.5 * (e.truth.I_Pcm_B[0] + e.truth.I_Pcm_B[3] + e.truth.I_Pcm_B[5]);
  EXPECT_GT(estimate.sigma.tail<6>().maxCoeff(), 0.1 * half_trace);
}

TEST(PayloadEstimatorTest, InvalidOptionsAndLogsThrow) {
  const PayloadExperiment e;
  PayloadEstimatorOptions options;
  options.link = 6;
  EXPECT_NE(testing::ExpectInvalid([&] { EstimatePayload(e.model, e.loaded, nullptr, options); }).find("link"),
            std::string::npos);
  TorqueLog short_tau = e.loaded;
  short_tau.motion.tau.conservativeResize(Eigen::NoChange, 5);
  EXPECT_NE(testing::ExpectInvalid([&] { EstimatePayload(e.model, short_tau, nullptr, {}); }).find("loaded log"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench
