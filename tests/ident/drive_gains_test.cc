#include "idbench/ident/drive_gains.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

constexpr double kPayloadMass = 2.5;  // [kg]

// The puma560 along the general motion (10 s at 100 Hz), unloaded and with a
// 2.5 kg payload off-centre on the last link; currents i = τ/K.
struct GainExperiment {
  RobotModel model = MakePuma560();
  Eigen::VectorXd gains_true = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, -6.2, 4.1).finished();  // [N m/A]
  Eigen::Vector3d payload_com{0.02, -0.03, 0.08};  // [m], last link frame
  Eigen::Matrix3d payload_inertia = (Eigen::Matrix3d() << 4e-3, 2e-4, -1e-4, 2e-4, 5e-3, 3e-4, -1e-4, 3e-4, 3e-3).finished();
  DriveGainOptions options;
  CurrentLog unloaded, loaded;

  GainExperiment() {
    options.friction = {.viscous = true, .coulomb = true, .rotor_inertia = true};
    options.payload_mass = kPayloadMass;
    const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
    const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
    unloaded = Currents(testing::SyntheticJointLog(model, *motion, t));
    const RobotModel with_payload = testing::WithPayload(model, kPayloadMass, payload_com, payload_inertia);
    loaded = Currents(testing::SyntheticJointLog(with_payload, *motion, t));
  }
  CurrentLog Currents(const JointLog& log) const {
    CurrentLog out;
    out.motion = log;
    out.current = log.tau.array().rowwise() / gains_true.transpose().array();
    return out;
  }
};

// Noise-free logs: the gains come back to 1e-6 (rounding: measured ~1e-12),
// the robot's base parameters and the payload's first moment M·c too.
TEST(DriveGainsTest, NoiseFreeUnloadedAndLoadedLogsRecoverTheGains) {
  const GainExperiment e;
  const DriveGainEstimate estimate = EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options);
  ASSERT_EQ(estimate.status, DriveGainStatus::kEstimated) << estimate.message;
  const double error = testing::RelativeError(estimate.gains, e.gains_true);
  std::printf("gain recovery: max |dK|/max |K| = %.3g, rank %d of %zu unknowns\n", error, estimate.rank,
              estimate.unknown_names.size());
  EXPECT_LT(error, 1e-6);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(estimate.gains[j], e.gains_true[j], 1e-6 * std::abs(e.gains_true[j]));
  EXPECT_LT(estimate.sigma.maxCoeff(), 1e-6 * e.gains_true.cwiseAbs().minCoeff());
  EXPECT_LT(estimate.unloaded_relative_error, 1e-9);
  EXPECT_LT(estimate.loaded_relative_error, 1e-9);
  // β: the robot's own base parameters, where determined.
  const Eigen::VectorXd beta_true =
      estimate.base.combination * StandardParameters(e.model, e.options.friction);
  for (int k = 0; k < estimate.base.n_base(); ++k) {
    if (!estimate.identifiable[static_cast<size_t>(k)]) continue;
    EXPECT_NEAR(estimate.beta[k], beta_true[k], 1e-6 * std::max(1.0, std::abs(beta_true[k]))) << estimate.base.names[k];
  }
  // The payload's first moment M·c where determined (the wrist's spherical
  // joint leaves some inertia combinations to the base parameters).
  const Eigen::Vector3d mc_true = kPayloadMass * e.payload_com;
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(estimate.payload[c])) continue;
    EXPECT_NEAR(estimate.payload[c], mc_true[c], 1e-6) << PayloadParameterNames()[c];
  }
}

// Noisy currents (σ 1 % of each joint's RMS current): each gain within 4σ of
// the truth, and σ is of the size the noise implies (not 0, not huge).
TEST(DriveGainsTest, NoisyCurrentsGiveGainsWithinTheirSigma) {
  GainExperiment e;
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (CurrentLog* log : {&e.unloaded, &e.loaded}) {
    const Eigen::VectorXd rms = (log->current.colwise().squaredNorm() / log->current.rows()).cwiseSqrt();
    for (Eigen::Index s = 0; s < log->current.rows(); ++s)
      for (int j = 0; j < 6; ++j) log->current(s, j) += 0.01 * rms[j] * normal(rng);
  }
  const DriveGainEstimate estimate = EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options);
  ASSERT_EQ(estimate.status, DriveGainStatus::kEstimated) << estimate.message;
  for (int j = 0; j < 6; ++j) {
    std::printf("K%d: %.5g (true %.5g), sigma %.3g\n", j + 1, estimate.gains[j], e.gains_true[j], estimate.sigma[j]);
    EXPECT_LE(std::abs(estimate.gains[j] - e.gains_true[j]), 4.0 * estimate.sigma[j]) << "K" << j + 1;
    EXPECT_GT(estimate.sigma[j], 1e-5 * std::abs(e.gains_true[j])) << "K" << j + 1;
    EXPECT_LT(estimate.sigma[j], 0.05 * std::abs(e.gains_true[j])) << "K" << j + 1;
  }
}

// A drive whose current reads zero in both logs: its gain is not determined,
// a status naming it, not a throw.
TEST(DriveGainsTest, GainWithoutCurrentIsNotIdentifiable) {
  GainExperiment e;
  e.unloaded.current.col(5).setZero();
  e.loaded.current.col(5).setZero();
  const DriveGainEstimate estimate = EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options);
  EXPECT_EQ(estimate.status, DriveGainStatus::kNotIdentifiable);
  EXPECT_NE(estimate.message.find("K6"), std::string::npos) << estimate.message;
  EXPECT_FALSE(std::isfinite(estimate.gains[5]));
}

TEST(DriveGainsTest, RejectsBadInput) {
  GainExperiment e;
  e.options.payload_mass = 0.0;
  EXPECT_THROW(EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options), std::invalid_argument);
  e.options.payload_mass = kPayloadMass;
  e.loaded.current = e.loaded.current.leftCols(5).eval();
  EXPECT_THROW(EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options), std::invalid_argument);
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// Currents with noise of 1 % of each joint's RMS current, seeded.
CurrentLog WithNoise(CurrentLog log, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const Eigen::VectorXd rms = (log.current.colwise().squaredNorm() / log.current.rows()).cwiseSqrt();
  for (Eigen::Index s = 0; s < log.current.rows(); ++s)
    for (Eigen::Index j = 0; j < log.current.cols(); ++j) log.current(s, j) += 0.01 * rms[j] * normal(rng);
  return log;
}

// The sweep's cases with 1 % current noise: the same log twice, a second
// unloaded recording as the loaded log, the two logs swapped. Each has full
// rank and a small %σ (6ab1a0b: kEstimated, gains of 1e-11, 1e13 or all
// negative); the checks that the data carry the gains refuse them. The right
// pair passes, its torques K·i at the robot file's scale: s = 1 up to the
// noise (and to rounding without noise, where K·i = W β_file exactly).
TEST(DriveGainsTest, GainsTheDataCannotCarryAreRefused) {
  const GainExperiment e;
  const CurrentLog unloaded = WithNoise(e.unloaded, 1), unloaded2 = WithNoise(e.unloaded, 3);
  const CurrentLog loaded = WithNoise(e.loaded, 2);
  const DriveGainEstimate good = EstimateDriveGains(e.model, unloaded, loaded, e.options);
  ASSERT_EQ(good.status, DriveGainStatus::kEstimated) << good.message;
  EXPECT_NEAR(good.torque_scale, 1.0, 0.01);
  EXPECT_GT(good.payload_signal_to_noise, 10.0);
  const DriveGainEstimate exact = EstimateDriveGains(e.model, e.unloaded, e.loaded, e.options);
  EXPECT_NEAR(exact.torque_scale, 1.0, 1e-9);
  struct Case {
    const char* name;
    const CurrentLog &unloaded, &loaded;
    const char* expected;
  };
  const Case cases[] = {
      {"the same log twice", unloaded, unloaded, "the payload's effect is not seen in the data"},
      {"two unloaded recordings", unloaded, unloaded2, "the payload's effect is not seen in the data"},
      {"swapped", loaded, unloaded, "the two logs look swapped"},
  };
  for (const Case& c : cases) {
    const DriveGainEstimate estimate = EstimateDriveGains(e.model, c.unloaded, c.loaded, e.options);
    std::printf("%s: payload/residual %.3g, torque scale %.3g, K1 %.3g\n", c.name, estimate.payload_signal_to_noise,
                estimate.torque_scale, estimate.gains[0]);
    EXPECT_EQ(estimate.status, DriveGainStatus::kNotObserved) << c.name;
    EXPECT_NE(estimate.message.find(c.expected), std::string::npos) << c.name << ": " << estimate.message;
  }
}

}  // namespace
}  // namespace idbench
