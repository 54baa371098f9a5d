// Conditioning of measured joint logs before joint-torque identification:
// zero-phase Butterworth low-pass filtering, O(h²) numerical derivatives for
// qd and qdd, and decimation. Signals are matrices, rows = samples and
// columns = channels (joints), each column processed on its own. A single
// signal is a one-column matrix: an Eigen::VectorXd converts to one and the
// result assigns back to one (Eigen::VectorXd y = FiltFilt(sos, x)). One
// signature per operation, so Eigen expressions bind without ambiguity.
//
// The filter matches SciPy: DesignButterworthLowPass(N, fc, fs) equals
// scipy.signal.butter(N, fc, fs=fs, output='sos') and FiltFilt equals
// scipy.signal.sosfiltfilt(sos, x) (odd padding, sosfilt_zi initial states)
// to rounding; for records too short for SciPy's default padding it equals
// sosfiltfilt(sos, x, padlen=n−1) where SciPy would refuse.
// References: Oppenheim & Schafer, Discrete-Time Signal Processing, §7.1
// (bilinear transform); Gustafsson, IEEE Trans. Signal Process. 44(4), 1996
// (forward–backward filtering).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "idbench/engine/measurements.h"

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
// so H(1) = 1 (unity DC gain) and |H| = 1/√2 at the cutoff, up to coefficient
// rounding, ~N·ε/K² (1e-12 for N = 4 at fc/fs = 0.01).
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

// Zero-phase filtering of each column, forward then backward
// (scipy.signal.sosfiltfilt along axis 0):
//   1. extend x at both ends by odd reflection about the end samples,
//      x[−i] = 2 x[0] − x[i] for i = 1..padlen (and likewise at the end),
//      padlen = 3·ntaps, reduced to n − 1 for shorter records;
//   2. filter forward, each section starting in the steady state of a constant
//      input equal to the first padded sample (sosfilt_zi), so a constant
//      passes unchanged;
//   3. filter the reversed result the same way and reverse back; drop the pad.
// The result has no phase lag and magnitude response |H(e^{jω})|². It is
// linear in x.
// End effects: the padding is short next to the filter's time constants
// (~fs/(2π fc) samples), so a signal with a slope at an end starts with a
// transient that decays over a few 1/fc. Measured for N = 4, fc = 10 Hz at
// 1 kHz on a 1 Hz sine: 16 % of the amplitude at the end sample, 3e-5 from
// 3/fc (300 samples) in. Discard about 3/fc at each end (5/fc for
// derivatives, see ProcessJointLog).
// Throws std::invalid_argument if a section is malformed (a0 ≠ 1, not finite,
// or a pole on or outside the unit circle) or x has fewer than
// FiltFiltMinSamples(sos) rows.
Eigen::MatrixXd FiltFilt(const SosMatrix& sos, const Eigen::MatrixXd& x);

// FiltFilt of a long signal in overlapping windows (streamed logs). A window
// x holds rows [w0, w0 + x.rows()) of a signal of n_total samples; at_start:
// w0 = 0, at_end: the window reaches the last sample. At a true end the
// window is padded exactly as FiltFilt pads the whole signal (the same
// padlen, from n_total); at an inner edge each pass starts in the steady
// state of the edge sample, an error that decays with the slowest pole. So
// the rows more than FiltFiltSettlingSamples(sos) inside the inner edges
// equal FiltFilt of the whole signal to ~tolerance × the signal's range (a
// window covering the whole signal equals it exactly). x is filtered in
// place. Throws std::invalid_argument for a malformed sos, n_total shorter
// than FiltFilt accepts, or a window at an end shorter than padlen + 1.
void FiltFiltWindow(const SosMatrix& sos, Eigen::Index n_total, bool at_start, bool at_end,
                    Eigen::Ref<Eigen::MatrixXd> x);

// Samples for the start-up error of one pass of sos to fall below
// `tolerance` of the step at the edge: ln(10⁻³·tolerance)/ln(r) for the
// largest pole radius r (1e-3 of margin for the cascade's polynomial
// factors), at least padlen + 2. Order 4, 10 Hz at 1 kHz: r = 0.97625, 1440
// samples. Throws std::invalid_argument for a malformed sos or tolerance
// outside (0, 1).
int FiltFiltSettlingSamples(const SosMatrix& sos, double tolerance = 1e-12);

// Derivatives of uniformly sampled columns with step dt [s], O(dt²) at every
// sample: central differences inside,
//   x'_i = (x_{i+1} − x_{i−1}) / (2 dt),    x''_i = (x_{i+1} − 2 x_i + x_{i−1}) / dt²,
// and second-order one-sided formulas at the two ends,
//   x'_0 = (−3 x_0 + 4 x_1 − x_2) / (2 dt),  x''_0 = (2 x_0 − 5 x_1 + 4 x_2 − x_3) / dt²
// (mirrored at the last sample). FirstDerivative is exact for quadratics,
// SecondDerivative for cubics. Throws std::invalid_argument unless dt > 0 and
// x has at least 3 (first) or 4 (second derivative) rows.
Eigen::MatrixXd FirstDerivative(const Eigen::MatrixXd& x, double dt);
Eigen::MatrixXd SecondDerivative(const Eigen::MatrixXd& x, double dt);

// Keeps every factor-th sample: rows 0, factor, 2·factor, … (ceil(n/factor)
// rows). Does NOT filter: the caller must remove content above the new Nyquist
// frequency fs/(2·factor) first (FiltFilt), else it aliases.
// Throws std::invalid_argument if factor < 1.
Eigen::MatrixXd Decimate(const Eigen::MatrixXd& x, int factor);

struct LogFilterOptions {
  int order = 4;            // Butterworth order N (1..8); filtfilt doubles its effect
  double cutoff_hz = 10.0;  // −3 dB cutoff of one pass [Hz]; −6 dB after filtfilt
  int decimation = 1;       // keep every decimation-th sample after filtering (≥ 1)
  // Time dropped at both ends after filtering, where the end transients bias
  // qdd (see ProcessJointLog); < 0 means the recommended 5/cutoff_hz.
  double trim_s = 0.0;      // [s]
  // Filter tau as well. Off when the identification filters the regressor
  // and the torques together instead (parallel filtering, Gautier 1997),
  // which keeps the two consistent across Coulomb-friction steps.
  bool filter_tau = true;

  static constexpr int kMaxOrder = 8;

  // Checks what can be checked without the sample rate; ProcessJointLog also
  // requires cutoff_hz < fs/(2·decimation).
  bool IsValid(std::string* why) const;
};

// Conditions a measured joint log for identification:
//   q_f = FiltFilt(q), qd = FirstDerivative(q_f), qdd = SecondDerivative(q_f),
//   tau_f = FiltFilt(tau) with the same filter (so the torque sees the same
//   zero-phase magnitude response as the accelerations), then every output,
//   t included, is decimated by options.decimation.
// The sample rate is fs = (n − 1)/(t[n−1] − t[0]). Sampling must be uniform:
// every step t[i] − t[i−1] must equal t[1] − t[0] within 1e-6 relative.
// The first and last few 1/fc seconds are not usable for identification: the
// filter's end transient and the odd padding (which flips the curvature at the
// ends) bias them, most of all qdd. Measured with the defaults on a smooth
// 0.3–1.3 Hz motion at 1 kHz: |qdd error| up to 56 rad/s² at the end samples
// (|qdd| ≤ 16), below 0.05 from 3/fc and 5e-4 from 5/fc in; drop 5/fc
// (0.5 s at 10 Hz) at each end.
// Throws std::invalid_argument if the options are invalid, cutoff_hz ≥
// fs/(2·decimation), sizes differ (q and tau must be t.size() × n_dof,
// n_dof ≥ 1), t is not increasing or not uniform (the message names the first
// offending sample index), or the record is shorter than the filter needs.
JointLog ProcessJointLog(const Eigen::VectorXd& t, const Eigen::MatrixXd& q, const Eigen::MatrixXd& tau,
                             const LogFilterOptions& options);
// The same on a log's t, q and tau, using what the log recorded: a recorded
// qd (log.qd non-empty) is filtered instead of differentiating q_f, and qdd is
// then FirstDerivative(FiltFilt(qd)) (one difference of a measured velocity
// rather than two of a position); a recorded qdd is filtered and used as is.
// Every signal thus passes through the same zero-phase filter. A log with both
// qd and qdd needs no filter and is not a case for this function (it would
// filter them anyway). Throws as above, and if a recorded qd/qdd is not
// t.size() × n_dof.
JointLog ProcessJointLog(const JointLog& log, const LogFilterOptions& options);

// Parallel filtering (Gautier 1997): the stacked regressor's columns and the
// torques pass through the same zero-phase low-pass, per joint; then the end
// transients are dropped and the rows decimated. For logs whose qd, qdd were
// estimated from q with that filter and whose torques were left unfiltered.
struct ParallelFilter {
  LogFilterOptions filter;   // order, cutoff, decimation and trim (< 0: 5/cutoff)
  double sample_rate_hz = 0; // of the log
};

// Parallel filtering of stacked equations (Gautier 1997): `rows` holds
// n_samples · n_channels rows interleaved by channel (row = sample·n_channels
// + channel), e.g. a stacked regressor with its torques as the last column.
// Each channel's rows are filtered column by column with the Butterworth of
// `options` (FiltFilt along the samples) at `sample_rate_hz`, then
// trim_s (< 0: 5/cutoff_hz) is dropped at both ends and every
// decimation-th sample kept; *rows is replaced by the kept samples' rows,
// still interleaved. Linear: filtering W and τ alike keeps W β = τ. Throws
// std::invalid_argument for invalid options, rows not a multiple of
// n_channels, or too few samples to trim.
void ParallelFilterStackedRows(const LogFilterOptions& options, double sample_rate_hz, int n_channels,
                               Eigen::MatrixXd* rows);

// Samples dropped at each end by the parallel filter: ⌈trim_s · sample_rate_hz⌉
// (trim_s < 0: 5/cutoff_hz).
Eigen::Index ParallelFilterTrimSamples(const LogFilterOptions& options, double sample_rate_hz);

// The samples of an n_samples record that ParallelFilterStackedRows keeps, in
// order: s = trim, trim + decimation, … < n_samples − trim, with trim =
// ⌈trim_s · sample_rate_hz⌉ (trim_s < 0: 5/cutoff_hz). Throws
// std::invalid_argument for invalid options or when no sample is left.
std::vector<Eigen::Index> ParallelFilterKeptSamples(const LogFilterOptions& options, double sample_rate_hz,
                                                    Eigen::Index n_samples);

}  // namespace idbench
