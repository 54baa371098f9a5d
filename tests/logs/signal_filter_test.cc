#include "idbench/logs/signal_filter.h"

#include "idbench/logs/overlap_windows.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace idbench {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// H(e^{jω}) = Π_i (b0 + b1 z⁻¹ + b2 z⁻²)/(a0 + a1 z⁻¹ + a2 z⁻²), ω in rad/sample.
Complex FrequencyResponse(const SosMatrix& sos, double omega) {
  const Complex z1 = std::polar(1.0, -omega);
  const Complex z2 = z1 * z1;
  Complex h = 1.0;
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    h *= (sos(i, 0) + sos(i, 1) * z1 + sos(i, 2) * z2) / (sos(i, 3) + sos(i, 4) * z1 + sos(i, 5) * z2);
  }
  return h;
}

// The analytic Butterworth magnitude after the bilinear transform,
// 1/√(1 + (tan(ω/2)/tan(ωc/2))^{2N}).
double ButterworthMagnitude(int order, double omega, double omega_c) {
  return 1.0 / std::sqrt(1.0 + std::pow(std::tan(omega / 2) / std::tan(omega_c / 2), 2 * order));
}

// Largest pole radius: roots of z² + a1 z + a2 in every section.
double MaxPoleRadius(const SosMatrix& sos) {
  double r = 0.0;
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    const Complex disc = std::sqrt(Complex(sos(i, 4) * sos(i, 4) - 4.0 * sos(i, 5)));
    r = std::max({r, std::abs((-sos(i, 4) + disc) / 2.0), std::abs((-sos(i, 4) - disc) / 2.0)});
  }
  return r;
}

// Coefficients of the product of the sections' numerators, in powers of z⁻¹.
Eigen::VectorXd NumeratorProduct(const SosMatrix& sos) {
  Eigen::VectorXd p = Eigen::VectorXd::Ones(1);
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(p.size() + 2);
    for (Eigen::Index k = 0; k < p.size(); ++k) q.segment(k, 3) += p(k) * sos.row(i).head<3>().transpose();
    p = q;
  }
  return p;
}

double RelativeError(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  return (actual - expected).norm() / expected.norm();
}

double Rms(const Eigen::MatrixXd& e) { return std::sqrt(e.squaredNorm() / static_cast<double>(e.size())); }

Eigen::VectorXd Sine(int n_samples, double fs, double f, double amplitude, double phase = 0.0) {
  Eigen::VectorXd x(n_samples);
  for (int i = 0; i < n_samples; ++i) x(i) = amplitude * std::sin(2 * kPi * f * i / fs + phase);
  return x;
}

// Least-squares amplitudes (in-phase a, quadrature b) of
// y ≈ a sin(2π f i/fs + φ) + b cos(2π f i/fs + φ) over samples [begin, end).
Eigen::Vector2d FitSine(const Eigen::VectorXd& y, double fs, double f, double phase, int begin, int end) {
  Eigen::MatrixXd A(end - begin, 2);
  for (int i = begin; i < end; ++i) {
    const double arg = 2 * kPi * f * i / fs + phase;
    A.row(i - begin) << std::sin(arg), std::cos(arg);
  }
  return A.colPivHouseholderQr().solve(y.segment(begin, end - begin));
}

template <typename F>
std::string ThrownMessage(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

// ─── Design ─────────────────────────────────────────────────────────────────

// Outputs of scipy.signal.butter(N, fc, fs=fs, output='sos') (SciPy 1.10.1),
// printed with 17 significant digits.
TEST(ButterworthDesignTest, MatchesScipyCoefficients) {
  SosMatrix scipy_4_10_1000(2, 6);
  scipy_4_10_1000 << 8.9848614639706458e-07, 1.7969722927941292e-06, 8.9848614639706458e-07, 1.0,
      -1.8866095826215064e+00, 8.9033973628402419e-01,  //
      1.0, 2.0, 1.0, 1.0, -1.9492159580258417e+00, 9.5306989532789088e-01;
  EXPECT_LT(RelativeError(DesignButterworthLowPass(4, 10.0, 1000.0), scipy_4_10_1000), 1e-15);

  // butter(2, 0.2): also the textbook example b = [0.0675 0.1349 0.0675],
  // a = [1 −1.1430 0.4128].
  SosMatrix scipy_2_02(1, 6);
  scipy_2_02 << 0.06745527388907192, 0.13491054777814385, 0.06745527388907192, 1.0, -1.1429805025399011,
      0.41280159809618877;
  EXPECT_LT(RelativeError(DesignButterworthLowPass(2, 0.2 * 500.0, 1000.0), scipy_2_02), 1e-15);

  // Odd order: real pole in the first section, the single zero in the last.
  SosMatrix scipy_3_10_1000(2, 6);
  scipy_3_10_1000 << 2.9146494465697660e-05, 5.8292988931395321e-05, 2.9146494465697660e-05, 1.0,
      -9.3906250581749229e-01, 0.0,  //
      1.0, 1.0, 0.0, 1.0, -1.9352943868599919e+00, 9.3912079880642396e-01;
  EXPECT_LT(RelativeError(DesignButterworthLowPass(3, 10.0, 1000.0), scipy_3_10_1000), 1e-15);
}

// Independent derivation: the textbook bilinear biquads. 1/(s² + 2ζ s + 1)
// with s = (1/K)(1 − z⁻¹)/(1 + z⁻¹), K = tan(π fc/fs), is
//   K²(1 + z⁻¹)² / (D + 2(K² − 1) z⁻¹ + (1 − 2ζK + K²) z⁻²),  D = 1 + 2ζK + K²,
// with ζ_k = sin(π(2k+1)/(2N)); the real pole of odd N, 1/(s + 1), gives
// K(1 + z⁻¹) / ((1 + K) + (K − 1) z⁻¹). Larger ζ = smaller pole radius =
// earlier section; the numerators multiply to gain·(1 + z⁻¹)^N.
TEST(ButterworthDesignTest, MatchesTextbookBiquadCascade) {
  for (int order = 1; order <= 8; ++order) {
    for (const double fc : {0.5, 10.0, 100.0, 450.0}) {
      SCOPED_TRACE("order " + std::to_string(order) + ", fc " + std::to_string(fc));
      const double K = std::tan(kPi * fc / 1000.0);
      std::vector<Eigen::Vector2d> a;  // (a1, a2), in section order
      double gain = 1.0;
      if (order % 2 == 1) {
        a.emplace_back((K - 1) / (1 + K), 0.0);
        gain *= K / (1 + K);
      }
      for (int k = order / 2 - 1; k >= 0; --k) {  // ζ_k decreases with k < N/2
        const double zeta = std::sin(kPi * (2 * k + 1) / (2.0 * order));
        const double D = 1 + 2 * zeta * K + K * K;
        a.emplace_back(2 * (K * K - 1) / D, (1 - 2 * zeta * K + K * K) / D);
        gain *= K * K / D;
      }
      const SosMatrix sos = DesignButterworthLowPass(order, fc, 1000.0);
      ASSERT_EQ(sos.rows(), static_cast<Eigen::Index>(a.size()));
      for (Eigen::Index i = 0; i < sos.rows(); ++i) {
        EXPECT_EQ(sos(i, 3), 1.0);
        EXPECT_NEAR(sos(i, 4), a[i](0), 1e-14);
        EXPECT_NEAR(sos(i, 5), a[i](1), 1e-14);
      }
      Eigen::VectorXd binomial = Eigen::VectorXd::Zero(2 * sos.rows() + 1);
      for (int k = 0; k <= order; ++k) binomial(k) = std::tgamma(order + 1) / std::tgamma(k + 1) / std::tgamma(order - k + 1);
      EXPECT_LT(RelativeError(NumeratorProduct(sos), gain * binomial), 1e-13);
    }
  }
}

// |H| = 1 at DC, 1/√2 at the cutoff and the analytic Butterworth magnitude
// at 399 frequencies in (0, π); all poles inside the unit circle. At DC each
// section's gain is Σb/(1 + a1 + a2) with a denominator ~K² = tan²(π fc/fs),
// so rounding the coefficients (ε) moves it by ~ε/K² per section: 3e-12 was
// measured for N = 8 at fc/fs = 1e-3, hence the tolerance N·ε/K² (≥ 1e-12).
TEST(ButterworthDesignTest, MagnitudeResponseIsButterworth) {
  const double fs = 1000.0;
  for (int order = 1; order <= 8; ++order) {
    for (const double fc : {1.0, 10.0, 100.0, 250.0, 450.0}) {
      SCOPED_TRACE("order " + std::to_string(order) + ", fc " + std::to_string(fc));
      const SosMatrix sos = DesignButterworthLowPass(order, fc, fs);
      const double omega_c = 2 * kPi * fc / fs;
      const double K = std::tan(omega_c / 2);
      const double tolerance = std::max(1e-12, order * kEps / (K * K));
      EXPECT_NEAR(std::abs(FrequencyResponse(sos, 0.0)), 1.0, tolerance);
      EXPECT_NEAR(FrequencyResponse(sos, 0.0).imag(), 0.0, 1e-15);
      EXPECT_NEAR(std::abs(FrequencyResponse(sos, omega_c)), 1.0 / std::sqrt(2.0), tolerance);
      double max_error = 0.0;
      for (int i = 1; i < 400; ++i) {
        const double omega = kPi * i / 400.0;
        max_error = std::max(max_error, std::abs(std::abs(FrequencyResponse(sos, omega)) -
                                                 ButterworthMagnitude(order, omega, omega_c)));
      }
      EXPECT_LT(max_error, 1e-10);
      EXPECT_LT(MaxPoleRadius(sos), 1.0);
      EXPECT_EQ(FiltFiltMinSamples(sos), order + 2);  // ntaps = N + 1
    }
  }
}

TEST(ButterworthDesignTest, RejectsBadArguments) {
  EXPECT_NE(ThrownMessage([] { DesignButterworthLowPass(0, 10, 1000); }).find("expected order in 1..8, got 0"),
            std::string::npos);
  EXPECT_NE(ThrownMessage([] { DesignButterworthLowPass(9, 10, 1000); }).find("got 9"), std::string::npos);
  EXPECT_NE(ThrownMessage([] { DesignButterworthLowPass(4, 10, 0); }).find("expected sample rate > 0"),
            std::string::npos);
  EXPECT_NE(ThrownMessage([] { DesignButterworthLowPass(4, 500, 1000); }).find("expected cutoff in (0, 500)"),
            std::string::npos);
  EXPECT_NE(ThrownMessage([] { DesignButterworthLowPass(4, 0, 1000); }).find("got 0"), std::string::npos);
  EXPECT_THROW(DesignButterworthLowPass(4, std::nan(""), 1000), std::invalid_argument);
}

// ─── Zero-phase filtering ───────────────────────────────────────────────────

// scipy.signal.sosfiltfilt(butter(3, 100, fs=1000, output='sos'), x) for a
// unit impulse at sample 5 of 16 (SciPy 1.10.1; default padlen 3·4 = 12):
// pins the padding and initial-condition conventions, odd order included.
TEST(FiltFiltTest, MatchesScipySosfiltfilt) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(16);
  x(5) = 1.0;
  Eigen::VectorXd scipy(16);
  scipy << -7.2247645937384419e-05, 5.3502322115712431e-02, 1.0841537301692583e-01, 1.6045822943759647e-01,
      1.9836948940586688e-01, 2.0905456365081043e-01, 1.8700972610884858e-01, 1.3959925137957266e-01,
      8.2864330378619025e-02, 3.2449155241601024e-02, -2.5490325789104141e-03, -2.0395517136913229e-02,
      -2.4319449855722316e-02, -1.9407675103746511e-02, -1.0275277993407349e-02, -6.3417155140324272e-05;
  EXPECT_LT(RelativeError(FiltFilt(DesignButterworthLowPass(3, 100, 1000), x), scipy), 1e-13);
}

// Steady-state initial conditions: a constant is a fixed point, also for
// records short enough that the padding is reduced (n − 1 < 3·ntaps). It is
// scaled by the DC gain squared, 1 within ~1e-12 at fc/fs = 0.01 (see above).
TEST(FiltFiltTest, ConstantPassesUnchanged) {
  const double c = -2.75;
  for (int order = 1; order <= 8; ++order) {
    const SosMatrix sos = DesignButterworthLowPass(order, 10.0, 1000.0);
    for (const int n : {FiltFiltMinSamples(sos), 3 * (order + 1), 1000}) {
      SCOPED_TRACE("order " + std::to_string(order) + ", n " + std::to_string(n));
      const Eigen::VectorXd x = Eigen::VectorXd::Constant(n, c);
      EXPECT_LT((FiltFilt(sos, x) - x).cwiseAbs().maxCoeff(), 1e-12 * std::abs(c));
    }
  }
}

// fs 1 kHz, 4th order at 10 Hz, 6 s. A 1 Hz sine has |H|² = 1 − 1e-8: in the
// middle 4 s it must equal the input (no lag: the quadrature part is ~0).
// Near the ends the filter starts from the steady state of a constant while
// the signal has a slope, and the default padding (15 samples) is too short
// to absorb that: the end samples are off by up to 16 % of the amplitude
// (measured 0.164), 3e-5 from 3/fc = 300 samples in.
TEST(FiltFiltTest, SineBelowCutoffPassesWithoutPhaseLag) {
  const double fs = 1000.0, f = 1.0, amplitude = 0.8, phase = 0.3;
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, fs);
  const Eigen::VectorXd x = Sine(6000, fs, f, amplitude, phase);
  const Eigen::VectorXd y = FiltFilt(sos, x);
  const double expected_gain = std::pow(ButterworthMagnitude(4, 2 * kPi * f / fs, 2 * kPi * 10.0 / fs), 2);
  EXPECT_NEAR(expected_gain, 1.0, 2e-8);
  EXPECT_LT((y - x).segment(1000, 4000).cwiseAbs().maxCoeff() / amplitude, 1e-6);
  const Eigen::Vector2d ab = FitSine(y, fs, f, phase, 1000, 5000);
  EXPECT_NEAR(ab(0) / amplitude, expected_gain, 1e-6);
  EXPECT_NEAR(ab(1) / amplitude, 0.0, 1e-6);
  EXPECT_LT((y - x).segment(300, 5400).cwiseAbs().maxCoeff() / amplitude, 1e-4);
  EXPECT_LT((y - x).cwiseAbs().maxCoeff() / amplitude, 0.2);
}

// A 40 Hz sine through the 10 Hz filter: forward and backward each scale by
// |H| = 3.8e-3, so the middle amplitude is |H|² A ≈ 1.47e-5 A, in phase.
TEST(FiltFiltTest, SineAboveCutoffIsAttenuatedByTheSquaredMagnitude) {
  const double fs = 1000.0, f = 40.0, amplitude = 1.0, phase = 1.1;
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, fs);
  const Eigen::VectorXd y = FiltFilt(sos, Sine(6000, fs, f, amplitude, phase));
  const double expected_gain = std::pow(ButterworthMagnitude(4, 2 * kPi * f / fs, 2 * kPi * 10.0 / fs), 2);
  EXPECT_NEAR(expected_gain, 1.47e-5, 0.01e-5);
  const Eigen::Vector2d ab = FitSine(y, fs, f, phase, 1000, 5000);
  EXPECT_NEAR(ab(0) / (expected_gain * amplitude), 1.0, 0.01);
  EXPECT_LT(std::abs(ab(1)) / (expected_gain * amplitude), 0.01);
}

TEST(FiltFiltTest, IsLinearAndFiltersColumnsIndependently) {
  const SosMatrix sos = DesignButterworthLowPass(5, 30.0, 1000.0);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd X(500, 3);
  for (double& v : X.reshaped()) v = normal(rng);
  const double alpha = 2.5, beta = -0.75;
  const Eigen::VectorXd combined = FiltFilt(sos, alpha * X.col(0) + beta * X.col(1));
  const Eigen::VectorXd superposed = alpha * FiltFilt(sos, X.col(0)) + beta * FiltFilt(sos, X.col(1));
  EXPECT_LT(RelativeError(combined, superposed), 1e-13);

  const Eigen::MatrixXd Y = FiltFilt(sos, X);
  for (Eigen::Index j = 0; j < X.cols(); ++j) EXPECT_EQ(Y.col(j), FiltFilt(sos, X.col(j)));
}

// One channel at a time, the textbook way (scipy's sosfiltfilt: odd
// extension, each section in transposed direct form II from the steady state
// of the pass's first sample, forward then on the reversed output): the
// reference the library's channels-side-by-side filter must equal bit for
// bit, whatever the number of columns (groups of 8 and a partial one here).
Eigen::VectorXd ReferenceFiltFilt(const SosMatrix& sos, const Eigen::VectorXd& x, Eigen::Index pad_start,
                                  Eigen::Index pad_end) {
  const Eigen::Index n = x.size();
  Eigen::VectorXd y(n + pad_start + pad_end);
  y.segment(pad_start, n) = x;
  for (Eigen::Index i = 1; i <= pad_start; ++i) y(pad_start - i) = 2.0 * x(0) - x(i);
  for (Eigen::Index i = 1; i <= pad_end; ++i) y(pad_start + n - 1 + i) = 2.0 * x(n - 1) - x(n - 1 - i);
  for (int pass = 0; pass < 2; ++pass) {
    double level = y(0);
    for (Eigen::Index i = 0; i < sos.rows(); ++i) {
      const double b0 = sos(i, 0), b1 = sos(i, 1), b2 = sos(i, 2), a1 = sos(i, 4), a2 = sos(i, 5);
      const double gain = (b0 + b1 + b2) / (1.0 + a1 + a2);
      double z1 = b2 - a2 * gain;
      double z0 = b1 + z1 - a1 * gain;
      z0 *= level, z1 *= level;
      for (double& v : y) {
        const double in = v, out = b0 * in + z0;
        z0 = b1 * in - a1 * out + z1;
        z1 = b2 * in - a2 * out;
        v = out;
      }
      level *= gain;
    }
    y.reverseInPlace();
  }
  return y.segment(pad_start, n);
}

TEST(FiltFiltTest, ColumnsSideBySideEqualOneChannelAtATime) {
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, 1000.0);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd X(3000, 19);
  for (double& v : X.reshaped()) v = normal(rng);
  const Eigen::Index pad = 3 * (FiltFiltMinSamples(sos) - 1);
  const Eigen::MatrixXd Y = FiltFilt(sos, X);
  for (Eigen::Index j = 0; j < X.cols(); ++j) EXPECT_EQ(Y.col(j), ReferenceFiltFilt(sos, X.col(j), pad, pad)) << j;
  // A window inside a longer signal: no padding at its inner edges.
  Eigen::MatrixXd window = X.middleRows(500, 2000);
  FiltFiltWindow(sos, 10000, false, false, window);
  for (Eigen::Index j = 0; j < X.cols(); ++j)
    EXPECT_EQ(window.col(j), ReferenceFiltFilt(sos, X.col(j).segment(500, 2000), 0, 0)) << j;
}

TEST(FiltFiltTest, RejectsTooShortRecordsAndMalformedSections) {
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, 1000.0);
  EXPECT_NE(ThrownMessage([&] { FiltFilt(sos, Eigen::VectorXd::Zero(5)); })
                .find("expected at least 6 samples for 2 sections, got 5"),
            std::string::npos);
  EXPECT_NO_THROW(FiltFilt(sos, Eigen::VectorXd::Zero(6)));
  SosMatrix bad = sos;
  bad(1, 3) = 2.0;
  EXPECT_NE(ThrownMessage([&] { FiltFilt(bad, Eigen::VectorXd::Zero(100)); }).find("expected a0 = 1"),
            std::string::npos);
  EXPECT_THROW(FiltFilt(SosMatrix(0, 6), Eigen::VectorXd::Zero(100)), std::invalid_argument);
  SosMatrix unstable = sos;
  unstable(0, 5) = 1.0;  // poles on the unit circle
  EXPECT_NE(ThrownMessage([&] { FiltFilt(unstable, Eigen::VectorXd::Zero(100)); }).find("expected a stable section"),
            std::string::npos);
}

// ─── Derivatives ────────────────────────────────────────────────────────────

// The O(h²) stencils are exact for quadratics (first derivative) and cubics
// (second derivative); only rounding remains, ~ε·|x|/h and ~ε·|x|/h².
TEST(DerivativeTest, ExactForLowDegreePolynomials) {
  const double dt = 0.01;
  const int n = 101;
  Eigen::VectorXd quadratic(n), d_quadratic(n), cubic(n), dd_cubic(n);
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    quadratic(i) = 0.3 - 1.2 * t + 2.5 * t * t;
    d_quadratic(i) = -1.2 + 5.0 * t;
    cubic(i) = 0.3 - 1.2 * t + 2.5 * t * t - 0.7 * t * t * t;
    dd_cubic(i) = 5.0 - 4.2 * t;
  }
  EXPECT_LT((FirstDerivative(quadratic, dt) - d_quadratic).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT((SecondDerivative(cubic, dt) - dd_cubic).cwiseAbs().maxCoeff(), 1e-9);
}

// x = sin(ωt + φ), 2 Hz, t ∈ [0, 1]. Leading error terms (Taylor):
//   first derivative, worst at an end:  (h²/3)·|x‴(0)| = (h²/3)·ω³·cos φ;
//   second derivative, inside:          (h²/12)·max|x⁗| = (h²/12)·ω⁴;
//   second derivative, at an end:       (11/12)·h²·|x⁗(0)|, plus an h³ term.
// Halving h divides the whole-record max error by 4; the one-sided second
// derivative's h³ term (relative size ~hω) still shows at h = 1/200 (4.29).
TEST(DerivativeTest, ErrorShrinksAsHSquared) {
  const double omega = 2 * kPi * 2.0, phase = 0.4;
  std::vector<double> first_errors, second_errors;
  for (const int n_steps : {200, 400, 800, 1600}) {
    SCOPED_TRACE("h = 1/" + std::to_string(n_steps));
    const double h = 1.0 / n_steps;
    Eigen::VectorXd x(n_steps + 1), dx(n_steps + 1), ddx(n_steps + 1);
    for (int i = 0; i <= n_steps; ++i) {
      x(i) = std::sin(omega * i * h + phase);
      dx(i) = omega * std::cos(omega * i * h + phase);
      ddx(i) = -omega * omega * std::sin(omega * i * h + phase);
    }
    const Eigen::VectorXd first_error = (FirstDerivative(x, h) - dx).cwiseAbs();
    const Eigen::VectorXd second_error = (SecondDerivative(x, h) - ddx).cwiseAbs();
    first_errors.push_back(first_error.maxCoeff());
    second_errors.push_back(second_error.maxCoeff());
    EXPECT_NEAR(first_errors.back() / (h * h / 3 * std::pow(omega, 3) * std::cos(phase)), 1.0, 0.03);
    EXPECT_NEAR(second_error.segment(1, n_steps - 1).maxCoeff() / (h * h / 12 * std::pow(omega, 4)), 1.0, 0.01);
  }
  for (size_t i = 1; i < first_errors.size(); ++i) {
    SCOPED_TRACE("refinement " + std::to_string(i));
    EXPECT_NEAR(first_errors[i - 1] / first_errors[i], 4.0, 0.1);
    EXPECT_NEAR(second_errors[i - 1] / second_errors[i], 4.0, 0.35);
  }
}

TEST(DerivativeTest, DifferentiatesEachColumnOnItsOwn) {
  Eigen::MatrixXd X(50, 2);
  for (int i = 0; i < 50; ++i) X.row(i) << std::sin(0.1 * i), std::exp(0.02 * i);
  const Eigen::MatrixXd D1 = FirstDerivative(X, 0.01), D2 = SecondDerivative(X, 0.01);
  for (Eigen::Index j = 0; j < 2; ++j) {
    EXPECT_EQ(D1.col(j), FirstDerivative(X.col(j), 0.01));
    EXPECT_EQ(D2.col(j), SecondDerivative(X.col(j), 0.01));
  }
}

TEST(DerivativeTest, RejectsBadInput) {
  EXPECT_NE(ThrownMessage([] { FirstDerivative(Eigen::VectorXd::Zero(2), 0.01); })
                .find("expected at least 3 samples, got 2"),
            std::string::npos);
  EXPECT_NE(ThrownMessage([] { SecondDerivative(Eigen::VectorXd::Zero(3), 0.01); })
                .find("expected at least 4 samples, got 3"),
            std::string::npos);
  EXPECT_NE(ThrownMessage([] { FirstDerivative(Eigen::VectorXd::Zero(10), 0.0); }).find("expected dt > 0"),
            std::string::npos);
  EXPECT_THROW(SecondDerivative(Eigen::MatrixXd::Zero(10, 2), -1.0), std::invalid_argument);
}

// ─── Decimation ─────────────────────────────────────────────────────────────

TEST(DecimateTest, KeepsEveryKthSample) {
  Eigen::MatrixXd X(10, 2);
  for (int i = 0; i < 10; ++i) X.row(i) << i, -i;
  const Eigen::MatrixXd Y = Decimate(X, 3);  // rows 0, 3, 6, 9
  ASSERT_EQ(Y.rows(), 4);
  EXPECT_EQ(Y.col(0), Eigen::Vector4d(0, 3, 6, 9));
  EXPECT_EQ(Y.col(1), Eigen::Vector4d(0, -3, -6, -9));
  EXPECT_EQ(Decimate(X.col(0), 4), Eigen::Vector3d(0, 4, 8));
  EXPECT_EQ(Decimate(X, 1), X);
  EXPECT_NE(ThrownMessage([&] { Decimate(X, 0); }).find("expected factor >= 1, got 0"), std::string::npos);
}

// ─── Joint-log front-end ────────────────────────────────────────────────────

TEST(LogFilterOptionsTest, IsValid) {
  std::string why;
  EXPECT_TRUE(LogFilterOptions{}.IsValid(&why));
  EXPECT_FALSE((LogFilterOptions{.order = 0}).IsValid(&why));
  EXPECT_EQ(why, "order: expected 1..8, got 0");
  EXPECT_FALSE((LogFilterOptions{.cutoff_hz = -1.0}).IsValid(&why));
  EXPECT_NE(why.find("cutoff_hz: expected > 0 Hz"), std::string::npos);
  EXPECT_FALSE((LogFilterOptions{.decimation = 0}).IsValid(&why));
  EXPECT_EQ(why, "decimation: expected >= 1, got 0");
  EXPECT_FALSE((LogFilterOptions{.order = 9}).IsValid(nullptr));
}

// A smooth two-joint multi-sine (0.3, 0.7, 1.3 Hz) with the analytic q, qd, qdd.
struct MultiSineLog {
  Eigen::VectorXd t;
  Eigen::MatrixXd q, qd, qdd, tau;
};

MultiSineLog MakeMultiSineLog(int n_samples, double fs) {
  const double f[3] = {0.3, 0.7, 1.3};                          // [Hz]
  const double a[2][3] = {{0.6, 0.3, 0.15}, {-0.4, 0.5, 0.2}};  // [rad]
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(n_samples, 2);
  MultiSineLog log{Eigen::VectorXd(n_samples), zero, zero, zero, zero};
  for (int i = 0; i < n_samples; ++i) {
    log.t(i) = i / fs;
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 3; ++k) {
        const double w = 2 * kPi * f[k], arg = w * log.t(i) + 0.5 * (j + k);
        log.q(i, j) += a[j][k] * std::sin(arg);
        log.qd(i, j) += a[j][k] * w * std::cos(arg);
        log.qdd(i, j) += -a[j][k] * w * w * std::sin(arg);
      }
    }
  }
  // A torque linear in the motion (inertia, viscous, spring), so band-limited like q.
  log.tau = 2.0 * log.qdd + 0.5 * log.qd + 3.0 * log.q;
  return log;
}

// Predicted RMS of the qdd noise: white position noise σ through filtfilt
// (|H|², the analytic Butterworth magnitude) and the second difference
// (4 sin²(ω/2)/h²):  var = σ²/π ∫₀^π |H(ω)|⁴ (4 sin²(ω/2)/h²)² dω (midpoint rule).
double PredictedQddNoiseRms(double sigma, double h, int order, double omega_c) {
  const int n = 100000;
  double integral = 0.0;
  for (int i = 0; i < n; ++i) {
    const double omega = kPi * (i + 0.5) / n;
    const double d2 = 4.0 * std::pow(std::sin(omega / 2), 2) / (h * h);
    integral += std::pow(ButterworthMagnitude(order, omega, omega_c), 4) * d2 * d2 * (kPi / n);
  }
  return sigma * std::sqrt(integral / kPi);
}

// σ = 1e-4 rad of white noise on q at 1 kHz, 6 s, 2 joints. Raw double
// differencing amplifies it to σ√6/h² = 245 rad/s² (measured 247.6). The
// default filter (4th order, 10 Hz, zero phase) predicts 0.0223 rad/s² of qdd
// noise (above); the signal itself passes (|H|² ≥ 1 − 1e-7 up to 1.3 Hz), so
// away from the ends the RMS error must match the prediction: measured 0.0242
// for this seed, 0.0195–0.0242 over 8 seeds, as expected for ~100 independent
// 10 Hz-bandwidth samples per joint (scatter ~7 %); bound ±20 %. The ends are
// biased by the filter's start-up and the odd padding (the curvature flips),
// which dominates the whole-record RMS: measured 2.60 rad/s², still ~100×
// below raw differencing; bound 3.
TEST(ProcessJointLogTest, FilteredAccelerationBeatsRawDifferencing) {
  const double fs = 1000.0, sigma = 1e-4;
  const int n = 6000;
  const MultiSineLog truth = MakeMultiSineLog(n, fs);
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  Eigen::MatrixXd q_measured = truth.q;
  for (double& v : q_measured.reshaped()) v += noise(rng);

  const LogFilterOptions options;  // 4th order, 10 Hz, no decimation
  const JointLog out = ProcessJointLog(truth.t, q_measured, truth.tau, options);
  ASSERT_EQ(out.qdd.rows(), n);
  ASSERT_EQ(out.qdd.cols(), 2);

  const double raw_rms = Rms(SecondDerivative(q_measured, 1.0 / fs) - truth.qdd);
  EXPECT_NEAR(raw_rms / (sigma * std::sqrt(6.0) * fs * fs), 1.0, 0.05);

  const double predicted = PredictedQddNoiseRms(sigma, 1.0 / fs, 4, 2 * kPi * 10.0 / fs);
  EXPECT_NEAR(predicted, 0.0223, 0.0001);
  const int margin = 500;  // 5/fc at each end
  const auto interior = [&](const Eigen::MatrixXd& e) { return Rms(e.middleRows(margin, n - 2 * margin)); };
  EXPECT_NEAR(interior(out.qdd - truth.qdd) / predicted, 1.0, 0.2);
  EXPECT_LT(interior(out.qdd - truth.qdd), 1e-3 * raw_rms);
  EXPECT_LT(Rms(out.qdd - truth.qdd), 3.0);

  // Positions and velocities the same way: predicted 1.34e-5 rad and
  // 4.58e-4 rad/s (measured 1.37e-5, 4.86e-4).
  EXPECT_LT(interior(out.q - truth.q), 1.2 * 1.34e-5);
  EXPECT_LT(interior(out.qd - truth.qd), 1.2 * 4.58e-4);
  // The torque shares the filter and is band-limited like q: it passes
  // (measured 7.5e-8 relative).
  EXPECT_LT(interior(out.tau - truth.tau), 1e-6 * Rms(truth.tau));
  EXPECT_EQ(out.t, truth.t);
}

// A recorded qd (as a robot controller logs it) with white noise σ_v: qdd is
// one difference of the filtered qd, so its noise is σ_v through |H|² and
// 2 sin(ω)/(2h) instead of σ_q through four sin²(ω/2)/h²; the recorded qd is
// filtered (not replaced), qdd follows it. The same noise level in rad/s as
// the position noise in rad above gives a ~50× smaller qdd error: measured
// interior RMS 4.9e-4 rad/s² vs 0.0242 from q; bound 2e-3. qd: measured
// 1.37e-5 rad/s (the 10 Hz share of σ_v = 1e-4); bound 0.2 σ_v.
TEST(ProcessJointLogTest, RecordedVelocityIsFilteredAndDifferentiatedOnce) {
  const double fs = 1000.0, sigma = 1e-4;
  const int n = 6000;
  const MultiSineLog truth = MakeMultiSineLog(n, fs);
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  JointLog recorded;
  recorded.t = truth.t;
  recorded.q = truth.q;
  recorded.qd = truth.qd;
  for (double& v : recorded.qd.reshaped()) v += noise(rng);
  recorded.tau = truth.tau;
  const JointLog out = ProcessJointLog(recorded, LogFilterOptions{});
  const int margin = 500;
  const auto interior = [&](const Eigen::MatrixXd& e) { return Rms(e.middleRows(margin, n - 2 * margin)); };
  EXPECT_LT(interior(out.qdd - truth.qdd), 2e-3);
  EXPECT_LT(interior(out.qd - truth.qd), 0.2 * sigma);  // filtered: 10 Hz of the 500 Hz band
  EXPECT_LT(interior(out.q - truth.q), 1e-7);
  // Not the derivative of q: a qd offset shows in qd, not in q.
  recorded.qd.array() += 1.0;
  EXPECT_NEAR(interior(ProcessJointLog(recorded, LogFilterOptions{}).qd - truth.qd), 1.0, 1e-3);
}

// Noise-free, the error left is the end transient; it decays with the
// filter's time constants: measured max |qdd error| 56 rad/s² at the ends
// (|qdd| ≤ 16 there), 0.031 from 3/fc = 300 samples in, 2.4e-4 from 5/fc.
TEST(ProcessJointLogTest, EndTransientsDecayWithinAFewTimeConstants) {
  const int n = 6000;
  const MultiSineLog truth = MakeMultiSineLog(n, 1000.0);
  const JointLog out = ProcessJointLog(truth.t, truth.q, truth.tau, {});
  const auto max_error_from = [&](const Eigen::MatrixXd& e, int margin) {
    return e.middleRows(margin, n - 2 * margin).cwiseAbs().maxCoeff();
  };
  EXPECT_LT(max_error_from(out.qdd - truth.qdd, 0), 60.0);
  EXPECT_LT(max_error_from(out.qdd - truth.qdd, 300), 0.05);
  EXPECT_LT(max_error_from(out.qdd - truth.qdd, 500), 5e-4);
  EXPECT_LT(max_error_from(out.qd - truth.qd, 500), 5e-5);
  EXPECT_LT(max_error_from(out.q - truth.q, 500), 1e-7);
}

TEST(ProcessJointLogTest, DecimationKeepsEveryKthFilteredSample) {
  const MultiSineLog log = MakeMultiSineLog(1001, 1000.0);
  const JointLog full = ProcessJointLog(log.t, log.q, log.tau, {.cutoff_hz = 20.0});
  const JointLog decimated = ProcessJointLog(log.t, log.q, log.tau, {.cutoff_hz = 20.0, .decimation = 5});
  ASSERT_EQ(decimated.t.size(), 201);
  EXPECT_EQ(decimated.t, Decimate(full.t, 5));
  EXPECT_EQ(decimated.q, Decimate(full.q, 5));
  EXPECT_EQ(decimated.qd, Decimate(full.qd, 5));
  EXPECT_EQ(decimated.qdd, Decimate(full.qdd, 5));
  EXPECT_EQ(decimated.tau, Decimate(full.tau, 5));
}

TEST(ProcessJointLogTest, RejectsNonUniformSamplingAndBadShapes) {
  const MultiSineLog log = MakeMultiSineLog(1000, 1000.0);
  Eigen::VectorXd t = log.t;
  t.tail(500).array() += 1e-5;  // one step 1 % long: t[500] − t[499]
  EXPECT_NE(ThrownMessage([&] { ProcessJointLog(t, log.q, log.tau, {}); }).find("at sample 500"),
            std::string::npos);
  t = log.t;
  t(1) = t(0);
  EXPECT_NE(ThrownMessage([&] { ProcessJointLog(t, log.q, log.tau, {}); }).find("expected increasing t"),
            std::string::npos);
  // A step off by 1e-7 relative is within the tolerance.
  t = log.t;
  t.tail(300).array() += 1e-10;
  EXPECT_NO_THROW(ProcessJointLog(t, log.q, log.tau, {}));

  EXPECT_NE(ThrownMessage([&] { ProcessJointLog(log.t, log.q.topRows(999), log.tau, {}); })
                .find("expected q and tau of 1000 rows"),
            std::string::npos);
  EXPECT_THROW(ProcessJointLog(log.t, log.q, log.tau.leftCols(1), {}), std::invalid_argument);
  EXPECT_NE(ThrownMessage([&] { ProcessJointLog(log.t, log.q, log.tau, {.order = 0}); })
                .find("log filter options: order: expected 1.."),
            std::string::npos);
  // 60 Hz would alias after decimation by 10 (new Nyquist 50 Hz).
  EXPECT_NE(ThrownMessage([&] { ProcessJointLog(log.t, log.q, log.tau, {.cutoff_hz = 60.0, .decimation = 10}); })
                .find("expected cutoff_hz < fs/(2·decimation) = 50"),
            std::string::npos);
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// The slowest pole of the default filter (order 4, 10 Hz at 1 kHz) decays by
// e per ~42 samples: 1e-15 takes ~1440.
TEST(FiltFiltWindowTest, SettlingFollowsTheSlowestPole) {
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, 1000.0);
  const double r = std::sqrt(sos(sos.rows() - 1, 5));
  EXPECT_NEAR(r, 0.97625, 1e-5);
  const int settling = FiltFiltSettlingSamples(sos);
  EXPECT_EQ(settling, static_cast<int>(std::ceil(std::log(1e-15) / std::log(r))) + 2);
  EXPECT_GT(FiltFiltSettlingSamples(DesignButterworthLowPass(4, 10.0, 2000.0)), settling);  // slower at a higher rate
  EXPECT_THROW(FiltFiltSettlingSamples(sos, 0.0), std::invalid_argument);
}

// A window covering the whole signal is FiltFilt exactly; overlapping windows
// with the settling margin give FiltFilt of the whole signal to 1e-12 of its
// range, at the ends too, whatever the block and push sizes (a block smaller
// than the margin, a last push of 1 sample).
TEST(FiltFiltWindowTest, OverlappingWindowsEqualTheWholeSignalsFiltFilt) {
  const Eigen::Index n = 9001;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.1);
  Eigen::MatrixXd x(n, 2);
  for (Eigen::Index s = 0; s < n; ++s) {
    const double t = 1e-3 * static_cast<double>(s);
    x.row(s) << std::sin(2.0 * t) + 0.3 * t + noise(rng), (s % 1500 < 700 ? 1.0 : -1.0) + noise(rng);
  }
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, 1000.0);
  const Eigen::MatrixXd whole = FiltFilt(sos, x);
  Eigen::MatrixXd same = x;
  FiltFiltWindow(sos, n, true, true, same);
  EXPECT_EQ(same, whole);

  const Eigen::Index margin = FiltFiltSettlingSamples(sos);
  const double range = x.cwiseAbs().maxCoeff();
  for (Eigen::Index block : {300, 2048, 9000}) {
    for (Eigen::Index push : {1000, 4500, 9000}) {
      OverlapWindows windows(n, 2, margin, block);
      Eigen::MatrixXd streamed(n, 2);
      auto filter = [&](Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0, Eigen::Index o1) {
        Eigen::MatrixXd y = window;
        FiltFiltWindow(sos, n, w0 == 0, w0 + y.rows() == n, y);
        streamed.middleRows(o0, o1 - o0) = y.middleRows(o0 - w0, o1 - o0);
      };
      for (Eigen::Index s = 0; s < n; s += push) windows.Push(x.middleRows(s, std::min(push, n - s)), filter);
      EXPECT_LT((streamed - whole).cwiseAbs().maxCoeff(), 1e-12 * range) << "block " << block << ", push " << push;
    }
  }
}

TEST(FiltFiltWindowTest, RejectsAWindowTooShortAtAnEnd) {
  const SosMatrix sos = DesignButterworthLowPass(4, 10.0, 1000.0);
  Eigen::MatrixXd x = Eigen::MatrixXd::Ones(10, 1);
  EXPECT_THROW(FiltFiltWindow(sos, 1000, true, false, x), std::invalid_argument);  // padlen 27
  EXPECT_THROW(FiltFiltWindow(sos, 5, true, true, x), std::invalid_argument);      // more rows than the signal
  EXPECT_NO_THROW(FiltFiltWindow(sos, 1000, false, false, x));
}

}  // namespace
}  // namespace idbench
