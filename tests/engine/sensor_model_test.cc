// The sensor model's torque noise (sensor_model.h) against independent
// truth: white noise is σ times the draws; coloured noise keeps σ, has the
// autocorrelation a^ℓ of a first-order low-pass, and its spectrum is down by
// half (−3 dB) at the band asked for; Measure adds exactly that noise.
#include "idbench/engine/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace idbench {
namespace {

// Sample autocorrelation of x at lag ℓ (mean removed).
double Autocorrelation(const std::vector<double>& x, size_t lag) {
  double mean = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  double c0 = 0.0, cl = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    c0 += (x[i] - mean) * (x[i] - mean);
    if (i >= lag) cl += (x[i] - mean) * (x[i - lag] - mean);
  }
  return cl / c0;
}

TEST(SensorModelTest, WhiteNoiseIsSigmaTimesTheDraws) {
  TorqueNoise noise({0.5, 0.05}, 2, 0.0, 1000.0);
  EXPECT_EQ(noise.correlation(), 0.0);
  for (int k = 0; k < 5; ++k) {
    const double e = 0.3 * k - 0.7;
    EXPECT_EQ(noise.Next(0, e), 0.5 * e);
    EXPECT_EQ(noise.Next(1, e), 0.05 * e);
  }
}

// 200 000 samples at 1 kHz coloured to 5 Hz: a = exp(−2π·5/1000) = 0.9691;
// σ within 3 % (the estimate's scatter for a correlation time of 32
// samples: ~√(2·64/200 000) = 2.5 %), lags 1 and 10 within 0.01.
TEST(SensorModelTest, ColouredNoiseKeepsSigmaAndHasTheLowPassAutocorrelation) {
  const double rate = 1000.0, band = 5.0, sigma = 0.5;
  TorqueNoise noise({sigma}, 1, band, rate);
  const double a = std::exp(-2.0 * std::numbers::pi * band / rate);
  EXPECT_NEAR(noise.correlation(), a, 1e-15);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::vector<double> x(200000);
  for (double& v : x) v = noise.Next(0, normal(rng));
  double ss = 0.0;
  for (double v : x) ss += v * v;
  EXPECT_NEAR(std::sqrt(ss / static_cast<double>(x.size())) / sigma, 1.0, 0.03);
  EXPECT_NEAR(Autocorrelation(x, 1), a, 0.01);
  EXPECT_NEAR(Autocorrelation(x, 10), std::pow(a, 10), 0.01);
  // The first sample is already stationary: over many starts its σ is σ.
  double first = 0.0;
  for (int start = 0; start < 20000; ++start) {
    TorqueNoise fresh({sigma}, 1, band, rate);
    const double v = fresh.Next(0, normal(rng));
    first += v * v / 20000.0;
  }
  EXPECT_NEAR(std::sqrt(first) / sigma, 1.0, 0.02);
}

// The AR(1) spectrum S(ω) ∝ 1/(1 − 2a cos ω + a²) falls to half of S(0) at
// cos ω = (1 + a² − 2(1 − a)²)/(2a): that frequency is the band asked for,
// to the bilinear-free discretisation's error (< 1 % below fs/20).
TEST(SensorModelTest, TheBandIsTheHalfPowerFrequency) {
  const double rate = 1000.0;
  for (double band : {1.0, 5.0, 20.0, 50.0}) {
    const TorqueNoise noise({1.0}, 1, band, rate);
    const double a = noise.correlation();
    const double omega = std::acos((1.0 + a * a - 2.0 * (1.0 - a) * (1.0 - a)) / (2.0 * a));
    EXPECT_NEAR(omega * rate / (2.0 * std::numbers::pi) / band, 1.0, 0.01) << band << " Hz";
  }
}

TEST(SensorModelTest, BandsOutsideZeroToNyquistAreRefused) {
  for (double band : {-1.0, 500.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    SensorOptions options;
    options.rate_hz = 1000.0;
    options.tau_noise = {0.1};
    options.tau_noise_bandwidth_hz = band;
    std::string why;
    EXPECT_FALSE(options.IsValid(1, 1e-3, &why)) << band;
    EXPECT_EQ(why.rfind("tau_noise_bandwidth_hz: expected 0 (white) or a band in (0, 500] Hz", 0), 0u) << why;
    EXPECT_THROW(TorqueNoise({0.1}, 1, band, 1000.0), std::invalid_argument);
  }
  EXPECT_THROW(TorqueNoise({0.1, 0.2}, 3, 0.0, 1000.0), std::invalid_argument);
  SensorOptions nyquist;
  nyquist.tau_noise_bandwidth_hz = 500.0;
  EXPECT_TRUE(nyquist.IsValid(1, 1e-3, nullptr));
}

// Measure adds the same noise: τ_measured − τ is TorqueNoise driven by the
// draws Measure takes (q before τ per sample; no q noise here: τ's only).
TEST(SensorModelTest, MeasureAddsTheColouredNoise) {
  SimulationLog log;
  log.dt = 1e-3;
  for (int s = 0; s < 2000; ++s) {
    LogStep step;
    step.t = s * log.dt;
    step.q = Eigen::VectorXd::Constant(2, 0.1 * s);
    step.qd = step.qdd = Eigen::VectorXd::Zero(2);
    step.tau = Eigen::VectorXd::Constant(2, std::sin(0.01 * s));
    log.steps.push_back(step);
  }
  SensorOptions options;
  options.tau_noise = {0.5, 0.05};
  options.tau_noise_bandwidth_hz = 10.0;
  options.seed = 3;
  const JointLog measured = Measure(log, options);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  TorqueNoise noise(options.tau_noise, 2, 10.0, 1000.0);
  for (int s = 0; s < 2000; ++s) {
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(measured.tau(s, j) - log.steps[static_cast<size_t>(s)].tau[j], noise.Next(j, normal(rng)), 1e-14)
          << s << ", " << j;
    }
  }
}

}  // namespace
}  // namespace idbench
