#include "idbench/logs/signal_filter.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

std::string Str(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

void CheckSos(const SosMatrix& sos) {
  if (sos.rows() == 0) throw std::invalid_argument("filter: expected at least one section, got 0");
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    if (sos(i, 3) != 1.0) {
      throw std::invalid_argument("filter: expected a0 = 1 in every section, got " + Str(sos(i, 3)) +
                                  " in section " + std::to_string(i));
    }
    if (!sos.row(i).allFinite()) {
      throw std::invalid_argument("filter: expected finite coefficients, section " + std::to_string(i) +
                                  " is not");
    }
    // Poles inside the unit circle (the stability triangle of z² + a1 z + a2);
    // also keeps the steady-state gain Σb/(1 + a1 + a2) finite.
    if (!(std::abs(sos(i, 5)) < 1.0 && std::abs(sos(i, 4)) < 1.0 + sos(i, 5))) {
      throw std::invalid_argument("filter: expected a stable section (|a2| < 1, |a1| < 1 + a2), got a1 = " +
                                  Str(sos(i, 4)) + ", a2 = " + Str(sos(i, 5)) + " in section " +
                                  std::to_string(i));
    }
  }
}

void CheckDerivativeInput(Eigen::Index n, double dt, Eigen::Index min_samples, const char* what) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw std::invalid_argument(std::string(what) + ": expected dt > 0, got " + Str(dt));
  }
  if (n < min_samples) {
    throw std::invalid_argument(std::string(what) + ": expected at least " + std::to_string(min_samples) +
                                " samples, got " + std::to_string(n));
  }
}

Eigen::Index FiltFiltPad(const SosMatrix& sos, Eigen::Index n) {
  return std::min<Eigen::Index>(3 * (FiltFiltMinSamples(sos) - 1), n - 1);
}

// Zero-phase filtering (FiltFilt's steps 1–3), kGroup channels at once: with
// pad_start and pad_end samples of odd extension at the two ends (0: none,
// the pass starts in the steady state of the end sample), each section in
// transposed direct form II,
//   y = b0 x + z0,  z0 ← b1 x − a1 y + z1,  z1 ← b2 x − a2 y,
// starting in the state it would have after an infinitely long constant
// input equal to the pass's first sample (scipy.signal.sosfilt_zi · x[0]).
// The channels' recursions run side by side through each sample (independent
// chains the processor overlaps, and vector instructions across channels)
// where one channel alone waits on each sample's multiply-add chain; each
// channel's operations and their order are those of a channel alone.
constexpr int kGroup = 8;
using GroupRow = Eigen::Array<double, 1, kGroup>;
using GroupBuffer = Eigen::Array<double, Eigen::Dynamic, kGroup, Eigen::RowMajor>;

// One section's recursion over n rows of kGroup channels from `row`, `step`
// rows at a time (−1: backward), from the state (z0, z1), in vectors of 4
// channels (GCC's vector extension: the arithmetic of a channel alone, lane
// by lane). Built also for AVX2 (a vector a register; no FMA, so the same
// roundings as the baseline build's SSE2 pairs), picked at run time where
// the processor has it.
using Lanes4 = double __attribute__((vector_size(32)));
static_assert(kGroup == 8, "two vectors of 4 channels a row");
[[gnu::target_clones("avx2", "default")]] void FilterGroupSection(double b0, double b1, double b2, double a1,
                                                                   double a2, double* z0, double* z1, double* row,
                                                                   Eigen::Index n, Eigen::Index step) {
  Lanes4 z0a, z0b, z1a, z1b;
  std::memcpy(&z0a, z0, sizeof z0a), std::memcpy(&z0b, z0 + 4, sizeof z0b);
  std::memcpy(&z1a, z1, sizeof z1a), std::memcpy(&z1b, z1 + 4, sizeof z1b);
  for (Eigen::Index k = 0; k < n; ++k, row += step * kGroup) {
    Lanes4 ina, inb;
    std::memcpy(&ina, row, sizeof ina), std::memcpy(&inb, row + 4, sizeof inb);
    const Lanes4 outa = b0 * ina + z0a, outb = b0 * inb + z0b;
    z0a = b1 * ina - a1 * outa + z1a, z0b = b1 * inb - a1 * outb + z1b;
    z1a = b2 * ina - a2 * outa, z1b = b2 * inb - a2 * outb;
    std::memcpy(row, &outa, sizeof outa), std::memcpy(row + 4, &outb, sizeof outb);
  }
  std::memcpy(z0, &z0a, sizeof z0a), std::memcpy(z0 + 4, &z0b, sizeof z0b);
  std::memcpy(z1, &z1a, sizeof z1a), std::memcpy(z1 + 4, &z1b, sizeof z1b);
}

// One pass of all sections over y's rows, forward or from the last row back,
// each section starting in the steady state of the pass's first row.
void FilterGroupSteadyStart(const SosMatrix& sos, bool backward, GroupBuffer* y) {
  const Eigen::Index n = y->rows();
  const Eigen::Index first = backward ? n - 1 : 0;
  GroupRow level = y->row(first);
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    const double b0 = sos(i, 0), b1 = sos(i, 1), b2 = sos(i, 2), a1 = sos(i, 4), a2 = sos(i, 5);
    // Steady state for a unit input: y = G = H_i(1); from the update
    // equations z1 = b2 − a2 G, z0 = b1 + z1 − a1 G.
    const double gain = (b0 + b1 + b2) / (1.0 + a1 + a2);
    const double z1_unit = b2 - a2 * gain;
    const double z0_unit = b1 + z1_unit - a1 * gain;
    GroupRow z0 = level * z0_unit, z1 = level * z1_unit;
    FilterGroupSection(b0, b1, b2, a1, a2, z0.data(), z1.data(), y->data() + first * kGroup, n, backward ? -1 : 1);
    level *= gain;
  }
}

// The zero-phase filter of every column of x, kGroup columns at a time.
void FiltFiltColumns(const SosMatrix& sos, Eigen::Ref<Eigen::MatrixXd> x, Eigen::Index pad_start,
                     Eigen::Index pad_end) {
  const Eigen::Index n = x.rows();
  GroupBuffer y(n + pad_start + pad_end, kGroup);
  for (Eigen::Index c0 = 0; c0 < x.cols(); c0 += kGroup) {
    const Eigen::Index width = std::min<Eigen::Index>(kGroup, x.cols() - c0);
    if (width < kGroup) y.setZero();  // unused channels of the last group stay 0
    // Row by row (each of y's rows one cache line, x's columns read in step).
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index g = 0; g < width; ++g) y(pad_start + i, g) = x(i, c0 + g);
    for (Eigen::Index g = 0; g < width; ++g) {
      const auto column = x.col(c0 + g);
      for (Eigen::Index i = 1; i <= pad_start; ++i) y(pad_start - i, g) = 2.0 * column(0) - column(i);
      for (Eigen::Index i = 1; i <= pad_end; ++i) y(pad_start + n - 1 + i, g) = 2.0 * column(n - 1) - column(n - 1 - i);
    }
    FilterGroupSteadyStart(sos, false, &y);
    FilterGroupSteadyStart(sos, true, &y);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index g = 0; g < width; ++g) x(i, c0 + g) = y(pad_start + i, g);
  }
}

}  // namespace

SosMatrix DesignButterworthLowPass(int order, double cutoff_hz, double sample_rate_hz) {
  if (order < 1 || order > LogFilterOptions::kMaxOrder) {
    throw std::invalid_argument("butterworth: expected order in 1.." + std::to_string(LogFilterOptions::kMaxOrder) +
                                ", got " + std::to_string(order));
  }
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw std::invalid_argument("butterworth: expected sample rate > 0 Hz, got " + Str(sample_rate_hz));
  }
  if (!(cutoff_hz > 0.0 && cutoff_hz < 0.5 * sample_rate_hz)) {
    throw std::invalid_argument("butterworth: expected cutoff in (0, " + Str(0.5 * sample_rate_hz) +
                                ") Hz (below fs/2), got " + Str(cutoff_hz));
  }
  using Complex = std::complex<double>;
  const double pi = std::numbers::pi;
  const int n_pairs = order / 2;
  const bool has_real_pole = order % 2 == 1;

  // Analog prototype poles on the unit circle, pre-warped so the digital
  // cutoff lands at fc, mapped by the bilinear transform. Only the upper
  // half-plane pole of each conjugate pair is kept.
  const double K = std::tan(pi * cutoff_hz / sample_rate_hz);
  Complex gain_denominator = 1.0;  // Π_k (1 − K s_k) over all N poles
  std::vector<Complex> pair_poles;
  for (int k = 0; k < n_pairs; ++k) {
    const double phi = pi * (2 * k + 1) / (2.0 * order);
    const Complex s(-std::sin(phi), std::cos(phi));
    pair_poles.push_back((1.0 + K * s) / (1.0 - K * s));
    gain_denominator *= (1.0 - K * s) * (1.0 - K * std::conj(s));
  }
  double real_pole = 0.0;
  if (has_real_pole) {
    real_pole = (1.0 - K) / (1.0 + K);
    gain_denominator *= 1.0 + K;
  }
  // Gain so that H(1) = 1: from H(z) ∝ Π (1 + z⁻¹) / Π (1 − z_k z⁻¹) with
  // the bilinear map, k = K^N / Re Π (1 − K s_k) (SciPy's bilinear_zpk).
  const double gain = std::pow(K, order) / gain_denominator.real();

  // Sections by increasing pole radius (the real pole is the smallest), each
  // with two zeros at z = −1. For odd N one section has a single zero; as in
  // SciPy's zpk2sos it is the last one, b = [1 1 0].
  std::sort(pair_poles.begin(), pair_poles.end(),
            [](const Complex& a, const Complex& b) { return std::abs(a) < std::abs(b); });
  const Eigen::Index n_sections = n_pairs + (has_real_pole ? 1 : 0);
  SosMatrix sos(n_sections, 6);
  Eigen::Index row = 0;
  if (has_real_pole) sos.row(row++) << 1.0, 2.0, 1.0, 1.0, -real_pole, 0.0;
  for (const Complex& p : pair_poles) sos.row(row++) << 1.0, 2.0, 1.0, 1.0, -2.0 * p.real(), std::norm(p);
  if (has_real_pole) sos.row(n_sections - 1).head<3>() << 1.0, 1.0, 0.0;
  sos.row(0).head<3>() *= gain;
  return sos;
}

int FiltFiltMinSamples(const SosMatrix& sos) {
  const auto n_zero_b2 = (sos.col(2).array() == 0.0).count();
  const auto n_zero_a2 = (sos.col(5).array() == 0.0).count();
  const int ntaps = static_cast<int>(2 * sos.rows() + 1 - std::min(n_zero_b2, n_zero_a2));
  return ntaps + 1;
}

Eigen::MatrixXd FiltFilt(const SosMatrix& sos, const Eigen::MatrixXd& x) {
  CheckSos(sos);
  const Eigen::Index n = x.rows();
  const int min_samples = FiltFiltMinSamples(sos);
  if (n < min_samples) {
    throw std::invalid_argument("filtfilt: expected at least " + std::to_string(min_samples) + " samples for " +
                                std::to_string(sos.rows()) + " sections, got " + std::to_string(n));
  }
  const Eigen::Index pad = FiltFiltPad(sos, n);
  Eigen::MatrixXd y = x;
  FiltFiltColumns(sos, y, pad, pad);
  return y;
}

int FiltFiltSettlingSamples(const SosMatrix& sos, double tolerance) {
  CheckSos(sos);
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw std::invalid_argument("filter settling: expected a tolerance in (0, 1), got " + Str(tolerance));
  }
  // The largest pole radius: √a2 for a complex pair (a1² < 4 a2), else the
  // larger root of z² + a1 z + a2.
  double radius = 0.0;
  for (Eigen::Index i = 0; i < sos.rows(); ++i) {
    const double a1 = sos(i, 4), a2 = sos(i, 5);
    const double discriminant = a1 * a1 - 4.0 * a2;
    const double r = discriminant < 0.0 ? std::sqrt(a2) : 0.5 * (std::abs(a1) + std::sqrt(discriminant));
    radius = std::max(radius, r);
  }
  // The sections in cascade multiply the slowest mode by a polynomial in k of
  // degree n_sections − 1 and by the ratio of the pole spacings; 1e-3 more of
  // decay covers both for the Butterworths of DesignButterworthLowPass.
  const double decay = radius > 0.0 ? std::log(1e-3 * tolerance) / std::log(radius) : 0.0;
  const int pad = 3 * (FiltFiltMinSamples(sos) - 1);
  return std::max(pad + 2, static_cast<int>(std::ceil(decay)) + 2);
}

void FiltFiltWindow(const SosMatrix& sos, Eigen::Index n_total, bool at_start, bool at_end,
                    Eigen::Ref<Eigen::MatrixXd> x) {
  CheckSos(sos);
  const Eigen::Index n = x.rows();
  const int min_samples = FiltFiltMinSamples(sos);
  if (n_total < min_samples || n > n_total || n < 2) {
    throw std::invalid_argument("filtfilt window: expected 2 <= " + std::to_string(n) + " rows <= " +
                                std::to_string(n_total) + " samples of a signal of at least " +
                                std::to_string(min_samples));
  }
  const Eigen::Index pad = FiltFiltPad(sos, n_total);
  if ((at_start || at_end) && n < pad + 1) {
    throw std::invalid_argument("filtfilt window: expected at least " + std::to_string(pad + 1) +
                                " rows at an end of the signal, got " + std::to_string(n));
  }
  FiltFiltColumns(sos, x, at_start ? pad : 0, at_end ? pad : 0);
}

Eigen::MatrixXd FirstDerivative(const Eigen::MatrixXd& x, double dt) {
  const Eigen::Index n = x.rows();
  CheckDerivativeInput(n, dt, 3, "first derivative");
  const double c = 1.0 / (2.0 * dt);
  Eigen::MatrixXd d(n, x.cols());
  d.row(0) = c * (-3.0 * x.row(0) + 4.0 * x.row(1) - x.row(2));
  d.middleRows(1, n - 2) = c * (x.bottomRows(n - 2) - x.topRows(n - 2));
  d.row(n - 1) = c * (3.0 * x.row(n - 1) - 4.0 * x.row(n - 2) + x.row(n - 3));
  return d;
}

Eigen::MatrixXd SecondDerivative(const Eigen::MatrixXd& x, double dt) {
  const Eigen::Index n = x.rows();
  CheckDerivativeInput(n, dt, 4, "second derivative");
  const double c = 1.0 / (dt * dt);
  Eigen::MatrixXd d(n, x.cols());
  d.row(0) = c * (2.0 * x.row(0) - 5.0 * x.row(1) + 4.0 * x.row(2) - x.row(3));
  d.middleRows(1, n - 2) = c * (x.bottomRows(n - 2) - 2.0 * x.middleRows(1, n - 2) + x.topRows(n - 2));
  d.row(n - 1) = c * (2.0 * x.row(n - 1) - 5.0 * x.row(n - 2) + 4.0 * x.row(n - 3) - x.row(n - 4));
  return d;
}

Eigen::MatrixXd Decimate(const Eigen::MatrixXd& x, int factor) {
  if (factor < 1) throw std::invalid_argument("decimate: expected factor >= 1, got " + std::to_string(factor));
  const Eigen::Index n_out = (x.rows() + factor - 1) / factor;
  Eigen::MatrixXd y(n_out, x.cols());
  for (Eigen::Index i = 0; i < n_out; ++i) y.row(i) = x.row(i * factor);
  return y;
}

bool LogFilterOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (order < 1 || order > kMaxOrder) {
    return fail("order: expected 1.." + std::to_string(kMaxOrder) + ", got " + std::to_string(order));
  }
  if (!(cutoff_hz > 0.0) || !std::isfinite(cutoff_hz)) {
    return fail("cutoff_hz: expected > 0 Hz, got " + Str(cutoff_hz));
  }
  if (decimation < 1) return fail("decimation: expected >= 1, got " + std::to_string(decimation));
  if (!std::isfinite(trim_s)) return fail("trim_s: expected a finite value, got " + Str(trim_s));
  return true;
}

namespace {

// ProcessJointLog on t, q, tau and, where recorded (non-empty), qd and qdd.
JointLog ProcessRecordedLog(const Eigen::VectorXd& t, const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd,
                            const Eigen::MatrixXd& qdd, const Eigen::MatrixXd& tau, const LogFilterOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("log filter options: " + why);

  // Shapes.
  const Eigen::Index n = t.size();
  if (q.rows() != n || tau.rows() != n || q.cols() != tau.cols() || q.cols() < 1) {
    throw std::invalid_argument("joint log: expected q and tau of " + std::to_string(n) +
                                " rows (t.size()) and equal n_dof >= 1 columns, got q " +
                                std::to_string(q.rows()) + "x" + std::to_string(q.cols()) + ", tau " +
                                std::to_string(tau.rows()) + "x" + std::to_string(tau.cols()));
  }
  for (const Eigen::MatrixXd* recorded : {&qd, &qdd}) {
    if (recorded->size() > 0 && (recorded->rows() != n || recorded->cols() != q.cols())) {
      throw std::invalid_argument("joint log: expected a recorded " + std::string(recorded == &qd ? "qd" : "qdd") +
                                  " of " + std::to_string(n) + "x" + std::to_string(q.cols()) + ", got " +
                                  std::to_string(recorded->rows()) + "x" + std::to_string(recorded->cols()));
    }
  }
  if (n < 2) throw std::invalid_argument("joint log: expected at least 2 samples, got " + std::to_string(n));
  if (!t.allFinite() || !q.allFinite() || !tau.allFinite() || !qd.allFinite() || !qdd.allFinite()) {
    throw std::invalid_argument("joint log: expected finite t, q and tau");
  }

  // Uniform sampling: every step equals the first one within 1e-6 relative.
  const double step0 = t(1) - t(0);
  if (!(step0 > 0.0)) {
    throw std::invalid_argument("joint log: expected increasing t, got t[1] - t[0] = " + Str(step0) + " s");
  }
  for (Eigen::Index i = 2; i < n; ++i) {
    const double step = t(i) - t(i - 1);
    if (std::abs(step - step0) > 1e-6 * step0) {
      throw std::invalid_argument("joint log: expected uniform sampling with step " + Str(step0) +
                                  " s (t[1] - t[0]), got t[" + std::to_string(i) + "] - t[" +
                                  std::to_string(i - 1) + "] = " + Str(step) + " s at sample " +
                                  std::to_string(i));
    }
  }
  const double dt = (t(n - 1) - t(0)) / static_cast<double>(n - 1);
  const double fs = 1.0 / dt;

  // The kept samples must not alias: the cutoff below the new Nyquist rate.
  const double nyquist_out = 0.5 * fs / options.decimation;
  if (!(options.cutoff_hz < nyquist_out)) {
    throw std::invalid_argument("joint log: expected cutoff_hz < fs/(2·decimation) = " + Str(nyquist_out) +
                                " Hz, got " + Str(options.cutoff_hz) + " Hz (fs = " + Str(fs) + " Hz)");
  }
  const SosMatrix sos = DesignButterworthLowPass(options.order, options.cutoff_hz, fs);

  // Filter, differentiate the filtered positions (or the filtered recorded
  // velocities), filter the torques alike.
  const Eigen::MatrixXd q_f = FiltFilt(sos, q);
  JointLog out;
  if (qd.size() > 0) {
    const Eigen::MatrixXd qd_f = FiltFilt(sos, qd);
    out.qdd = Decimate(qdd.size() > 0 ? FiltFilt(sos, qdd) : FirstDerivative(qd_f, dt), options.decimation);
    out.qd = Decimate(qd_f, options.decimation);
  } else {
    out.qd = Decimate(FirstDerivative(q_f, dt), options.decimation);
    out.qdd = Decimate(qdd.size() > 0 ? FiltFilt(sos, qdd) : SecondDerivative(q_f, dt), options.decimation);
  }
  out.q = Decimate(q_f, options.decimation);
  out.tau = Decimate(options.filter_tau ? FiltFilt(sos, tau) : tau, options.decimation);
  out.t = Decimate(t, options.decimation);
  // Drop the ends, where the filter's transients bias the derivatives.
  const double trim = options.trim_s < 0.0 ? 5.0 / options.cutoff_hz : options.trim_s;
  if (trim > 0.0) {
    const Eigen::Index kept_first = (out.t.array() < out.t[0] + trim).count();
    const Eigen::Index kept_end = (out.t.array() <= out.t[out.t.size() - 1] - trim).count();
    if (kept_end <= kept_first) {
      throw std::invalid_argument("joint log: " + Str(t(n - 1) - t(0)) + " s is too short to trim " + Str(trim) +
                                  " s of filter transients at both ends");
    }
    const Eigen::Index m = kept_end - kept_first;
    out.t = out.t.segment(kept_first, m).eval();
    for (Eigen::MatrixXd* x : {&out.q, &out.qd, &out.qdd, &out.tau}) *x = x->middleRows(kept_first, m).eval();
  }
  return out;
}

}  // namespace

JointLog ProcessJointLog(const Eigen::VectorXd& t, const Eigen::MatrixXd& q, const Eigen::MatrixXd& tau,
                         const LogFilterOptions& options) {
  return ProcessRecordedLog(t, q, Eigen::MatrixXd(), Eigen::MatrixXd(), tau, options);
}

JointLog ProcessJointLog(const JointLog& log, const LogFilterOptions& options) {
  return ProcessRecordedLog(log.t, log.q, log.qd, log.qdd, log.tau, options);
}

void ParallelFilterStackedRows(const LogFilterOptions& options, double sample_rate_hz, int n_channels,
                               Eigen::MatrixXd* rows) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("parallel filter options: " + why);
  if (n_channels < 1 || rows->rows() % n_channels != 0) {
    throw std::invalid_argument("parallel filter: expected rows in whole samples of " + std::to_string(n_channels) +
                                " channels, got " + std::to_string(rows->rows()) + " rows");
  }
  const Eigen::Index n_samples = rows->rows() / n_channels;
  const SosMatrix sos = DesignButterworthLowPass(options.order, options.cutoff_hz, sample_rate_hz);
  // Per channel: the samples of that channel's rows, every column alike.
  using Strided = Eigen::Map<Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  for (int j = 0; j < n_channels; ++j) {
    Strided channel(rows->data() + j, n_samples, rows->cols(),
                    Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(rows->rows(), n_channels));
    channel = FiltFilt(sos, channel);
  }
  // Drop the transients at both ends, then keep every k-th sample.
  const std::vector<Eigen::Index> kept = ParallelFilterKeptSamples(options, sample_rate_hz, n_samples);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(kept.size()) * n_channels, rows->cols());
  for (size_t k = 0; k < kept.size(); ++k) {
    out.middleRows(static_cast<Eigen::Index>(k) * n_channels, n_channels) = rows->middleRows(kept[k] * n_channels, n_channels);
  }
  *rows = std::move(out);
}

Eigen::Index ParallelFilterTrimSamples(const LogFilterOptions& options, double sample_rate_hz) {
  const double trim_s = options.trim_s < 0.0 ? 5.0 / options.cutoff_hz : options.trim_s;
  return static_cast<Eigen::Index>(std::ceil(trim_s * sample_rate_hz - 1e-9));
}

std::vector<Eigen::Index> ParallelFilterKeptSamples(const LogFilterOptions& options, double sample_rate_hz,
                                                    Eigen::Index n_samples) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("parallel filter options: " + why);
  const Eigen::Index trim = ParallelFilterTrimSamples(options, sample_rate_hz);
  if (n_samples - 2 * trim < 1) {
    throw std::invalid_argument("joint log: " + std::to_string(n_samples) + " samples are too few to drop " +
                                std::to_string(trim) + " filter-transient samples at both ends");
  }
  std::vector<Eigen::Index> kept;
  for (Eigen::Index s = trim; s < n_samples - trim; s += options.decimation) kept.push_back(s);
  return kept;
}

}  // namespace idbench
