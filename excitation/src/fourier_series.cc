#include "idbench/excitation/fourier_series.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "quintic_hermite.h"

namespace idbench {
namespace {

// Column k of the plain Fourier sum's weights at t: coefficient a_l (k = l − 1)
// or b_l (k = H + l − 1), with its first and second derivative.
struct FourierTerm {
  double q, qd, qdd;
};

FourierTerm Term(double t, double wf, int harmonics, int k) {
  const int l = k % harmonics + 1;
  const double w = wf * l;
  const double s = std::sin(w * t), c = std::cos(w * t);
  if (k < harmonics) return {s / w, c, -w * s};  // a_l: sin(ωt)/ω
  return {-c / w, s, w * c};                      // b_l: −cos(ωt)/ω
}

}  // namespace

FourierSeriesTrajectory::FourierSeriesTrajectory(Eigen::VectorXd q0, Eigen::MatrixXd a, Eigen::MatrixXd b,
                                                 double f0, double duration, bool rest_to_rest)
    : q0_(std::move(q0)), a_(std::move(a)), b_(std::move(b)), f0_(f0), duration_(duration),
      rest_to_rest_(rest_to_rest) {
  if (a_.rows() != q0_.size() || b_.rows() != q0_.size() || a_.cols() != b_.cols() || a_.cols() < 1) {
    throw std::invalid_argument("Fourier series: expected a and b of size " + std::to_string(q0_.size()) +
                                " x H (H >= 1), got " + std::to_string(a_.rows()) + "x" +
                                std::to_string(a_.cols()) + " and " + std::to_string(b_.rows()) + "x" +
                                std::to_string(b_.cols()));
  }
  if (!(f0_ > 0.0) || !std::isfinite(f0_)) throw std::invalid_argument("Fourier series: f0 must be > 0");
  if (!(duration_ > 0.0) || !std::isfinite(duration_))
    throw std::invalid_argument("Fourier series: duration must be > 0");
}

void FourierSeriesTrajectory::BasisAt(double t, double f0, int harmonics, double duration, bool rest_to_rest,
                                      FourierBasis* basis) {
  const int n = 2 * harmonics;
  basis->q.resize(n);
  basis->qd.resize(n);
  basis->qdd.resize(n);
  const double wf = 2.0 * std::numbers::pi * f0;
  // Rest-to-rest weights of the quintic at t, shared by all columns.
  internal::QuinticHermiteWeights h{};
  if (rest_to_rest) h = internal::QuinticHermite(t, duration);
  for (int k = 0; k < n; ++k) {
    const FourierTerm f = Term(t, wf, harmonics, k);
    basis->q[k] = f.q;
    basis->qd[k] = f.qd;
    basis->qdd[k] = f.qdd;
    if (!rest_to_rest) continue;
    // The quintic's end conditions (p0, v0, a0, p1, v1, a1) for this column.
    const FourierTerm f_start = Term(0.0, wf, harmonics, k), f_end = Term(duration, wf, harmonics, k);
    const double ends[6] = {0.0, -f_start.qd, -f_start.qdd, f_start.q - f_end.q, -f_end.qd, -f_end.qdd};
    for (int i = 0; i < 6; ++i) {
      basis->q[k] += h.q[i] * ends[i];
      basis->qd[k] += h.qd[i] * ends[i];
      basis->qdd[k] += h.qdd[i] * ends[i];
    }
  }
}

FourierBasis FourierSeriesTrajectory::BasisAt(double t, double f0, int harmonics, double duration,
                                              bool rest_to_rest) {
  FourierBasis basis;
  BasisAt(t, f0, harmonics, duration, rest_to_rest, &basis);
  return basis;
}

void FourierSeriesTrajectory::Evaluate(double t, JointState* state) const {
  const int h = harmonics();
  const FourierBasis w = BasisAt(t, f0_, h, duration_, rest_to_rest_);
  state->q = q0_ + a_ * w.q.head(h) + b_ * w.q.tail(h);
  state->qd = a_ * w.qd.head(h) + b_ * w.qd.tail(h);
  state->qdd = a_ * w.qdd.head(h) + b_ * w.qdd.tail(h);
}

}  // namespace idbench
