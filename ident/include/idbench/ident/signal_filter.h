// Conditioning of measured joint logs before joint-torque identification:
// zero-phase Butterworth low-pass filtering, O(h²) numerical derivatives for
// qd and qdd, and decimation. Signals are column-wise: rows = samples,
// columns = channels (joints); a Eigen::VectorXd is one channel.
//
// The filter matches SciPy: DesignButterworthLowPass(N, fc, fs) equals
// scipy.signal.butter(N, fc, fs=fs, output='sos') and FiltFilt equals
// scipy.signal.sosfiltfilt(sos, x) (odd padding, sosfilt_zi initial states)
// whenever the record is longer than SciPy's default padding.
// References: Oppenheim & Schafer, Discrete-Time Signal Processing, §7.1
// (bilinear transform); Gustafsson, IEEE Trans. Signal Process. 44(4), 1996
// (forward–backward filtering).
#pragma once

#include <string>

#include <Eigen/Core>

namespace idbench {

// Second-order sections, one per row: [b0 b1 b2 a0 a1 a2] with a0 = 1, each
//   H_i(z) = (b0 + b1 z⁻¹ + b2 z⁻²) / (1 + a1 z⁻¹ + a2 z⁻²),
// H(z) = Π_i H_i(z).
using SosMatrix = Eigen::Matrix<double, Eigen::Dynamic, 6>;

// Digital Butterworth low-pass of order `order` (1..8) with −3 dB cutoff
// `cutoff_hz` at sample rate `sample_rate_hz` (0 < cutoff_hz < sample_rate_hz/2):
// analog prototype poles s_k = −sin φ_k + j cos φ_k, φ_k = π(2k+1)/(2N),
// pre-warped by K = tan(π fc/fs) and mapped by the bilinear transform
// z_k = (1 + K s_k)/(1 − K s_k); all N zeros at z = −1. Then
//   |H(e^{jω})|² = 1 / (1 + (tan(ω/2) / tan(ωc/2))^{2N}),  ωc = 2π fc/fs,
// so H(1) = 1 (unity DC gain) and |H| = 1/√2 at the cutoff.
// Layout as SciPy's zpk2sos: ceil(N/2) sections ordered by increasing pole
// radius, so the poles closest to the unit circle are last; for odd N the
// real pole (a2 = 0) is in the first section and the single zero (b = [1 1 0])
// in the last. The overall gain is in the first section's b, the others
// have b = [1 2 1].
// Throws std::invalid_argument ("expected …, got …") for a bad order, rate or
// cutoff.
SosMatrix DesignButterworthLowPass(int order, double cutoff_hz, double sample_rate_hz);

// The fewest samples FiltFilt accepts: ntaps + 1, where the filter length
// ntaps = 2·n_sections + 1 − min(#sections with b2 = 0, #sections with a2 = 0)
// as in SciPy (N + 1 for a Butterworth of order N).
int FiltFiltMinSamples(const SosMatrix& sos);

// Zero-phase filtering, forward then backward (scipy.signal.sosfiltfilt):
//   1. extend x at both ends by odd reflection about the end samples,
//      x[−i] = 2 x[0] − x[i] for i = 1..padlen (and likewise at the end),
//      padlen = 3·ntaps, reduced to n − 1 for shorter records;
//   2. filter forward, each section starting in the steady state of a constant
//      input equal to the first padded sample (sosfilt_zi), so constants and
//      the value at the ends pass without a start-up transient;
//   3. filter the reversed result the same way and reverse back; drop the pad.
// The result has no phase lag and magnitude response |H(e^{jω})|². It is
// linear in x. Near the ends (about padlen samples) the odd extension shapes
// the result: value and slope are kept, curvature is not.
// Throws std::invalid_argument if the sections are malformed (a0 ≠ 1) or x has
// fewer than FiltFiltMinSamples(sos) samples.
Eigen::VectorXd FiltFilt(const SosMatrix& sos, const Eigen::VectorXd& x);
// Each column of x (rows = samples) filtered as above.
Eigen::MatrixXd FiltFilt(const SosMatrix& sos, const Eigen::MatrixXd& x);

// Derivatives of a uniformly sampled signal with step dt [s], O(dt²) at every
// sample: central differences inside,
//   x'_i = (x_{i+1} − x_{i−1}) / (2 dt),    x''_i = (x_{i+1} − 2 x_i + x_{i−1}) / dt²,
// and second-order one-sided formulas at the two ends,
//   x'_0 = (−3 x_0 + 4 x_1 − x_2) / (2 dt),  x''_0 = (2 x_0 − 5 x_1 + 4 x_2 − x_3) / dt²
// (mirrored at the last sample). FirstDerivative is exact for quadratics,
// SecondDerivative for cubics. Throws std::invalid_argument unless dt > 0 and
// x has at least 3 (first) or 4 (second derivative) samples.
Eigen::VectorXd FirstDerivative(const Eigen::VectorXd& x, double dt);
Eigen::MatrixXd FirstDerivative(const Eigen::MatrixXd& x, double dt);  // per column
Eigen::VectorXd SecondDerivative(const Eigen::VectorXd& x, double dt);
Eigen::MatrixXd SecondDerivative(const Eigen::MatrixXd& x, double dt);  // per column

// Keeps every factor-th sample: rows 0, factor, 2·factor, … (ceil(n/factor)
// rows). Does NOT filter: the caller must remove content above the new Nyquist
// frequency fs/(2·factor) first (or use FilterAndDecimate), else it aliases.
// Throws std::invalid_argument if factor < 1.
Eigen::VectorXd Decimate(const Eigen::VectorXd& x, int factor);
Eigen::MatrixXd Decimate(const Eigen::MatrixXd& x, int factor);

// Anti-aliased decimation: FiltFilt with a Butterworth of `order` cut off at
// 0.8 × the new Nyquist frequency, 0.8·fs/(2·factor), then Decimate. factor 1
// returns x unchanged. Throws std::invalid_argument for factor < 1 or as
// DesignButterworthLowPass / FiltFilt.
Eigen::MatrixXd FilterAndDecimate(const Eigen::MatrixXd& x, int factor, int order = 8);

struct LogFilterOptions {
  int order = 4;            // Butterworth order N (1..8); filtfilt doubles its effect
  double cutoff_hz = 10.0;  // −3 dB cutoff of one pass [Hz]; −6 dB after filtfilt
  int decimation = 1;       // keep every decimation-th sample after filtering (≥ 1)

  static constexpr int kMaxOrder = 8;

  // Checks what can be checked without the sample rate; ProcessJointLog also
  // requires cutoff_hz < fs/(2·decimation).
  bool IsValid(std::string* why) const;
};

// A conditioned log; rows = samples, columns = joints.
struct JointSignals {
  Eigen::VectorXd t;    // sample times [s] (n_samples)
  Eigen::MatrixXd q;    // filtered joint positions [rad] (n_samples × n_dof)
  Eigen::MatrixXd qd;   // velocities from the filtered q [rad/s]
  Eigen::MatrixXd qdd;  // accelerations from the filtered q [rad/s²]
  Eigen::MatrixXd tau;  // filtered joint torques [N m]
};

// Conditions a measured joint log for identification:
//   q_f = FiltFilt(q), qd = FirstDerivative(q_f), qdd = SecondDerivative(q_f),
//   tau_f = FiltFilt(tau) with the same filter (so the torque sees the same
//   zero-phase magnitude response as the accelerations), then every output,
//   t included, is decimated by options.decimation.
// The sample rate is fs = (n − 1)/(t[n−1] − t[0]). Sampling must be uniform:
// every step t[i] − t[i−1] must equal t[1] − t[0] within 1e-6 relative.
// Throws std::invalid_argument if the options are invalid, cutoff_hz ≥
// fs/(2·decimation), sizes differ (q and tau must be t.size() × n_dof,
// n_dof ≥ 1), t is not increasing or not uniform (the message names the first
// offending sample index), or the record is shorter than the filter needs.
JointSignals ProcessJointLog(const Eigen::VectorXd& t, const Eigen::MatrixXd& q, const Eigen::MatrixXd& tau,
                             const LogFilterOptions& options);

}  // namespace idbench
