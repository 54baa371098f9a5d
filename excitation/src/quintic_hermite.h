// Quintic Hermite interpolation on one interval (internal to the excitation
// module): the unique quintic p on [0, h] with given p, p', p'' at both ends,
//   p(τ) = p0 H0(s) + v0 h H1(s) + a0 h² H2(s) + a1 h² H3(s) + v1 h H4(s) + p1 H5(s),  s = τ/h.
// It reproduces every polynomial of degree ≤ 5 exactly (so also a cubic spline
// given its knot values, slopes and second derivatives).
#pragma once

namespace idbench::internal {

// Weights of (p0, v0, a0, p1, v1, a1) in p(τ), p'(τ), p''(τ).
struct QuinticHermiteWeights {
  double q[6], qd[6], qdd[6];
};

// τ: time since the interval's start [s] (may lie outside [0, h]: the
// polynomial is extended); h > 0: interval length [s].
inline QuinticHermiteWeights QuinticHermite(double tau, double h) {
  const double s = tau / h, s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const double h2 = h * h;
  QuinticHermiteWeights w;
  // p0 (and p1 = 1 − H0)
  const double H0 = 1 - 10 * s3 + 15 * s4 - 6 * s5;
  const double dH0 = (-30 * s2 + 60 * s3 - 30 * s4) / h;
  const double ddH0 = (-60 * s + 180 * s2 - 120 * s3) / h2;
  w.q[0] = H0, w.qd[0] = dH0, w.qdd[0] = ddH0;
  w.q[3] = 1 - H0, w.qd[3] = -dH0, w.qdd[3] = -ddH0;
  // v0
  w.q[1] = h * (s - 6 * s3 + 8 * s4 - 3 * s5);
  w.qd[1] = 1 - 18 * s2 + 32 * s3 - 15 * s4;
  w.qdd[1] = (-36 * s + 96 * s2 - 60 * s3) / h;
  // a0
  w.q[2] = h2 * (0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5);
  w.qd[2] = h * (s - 4.5 * s2 + 6 * s3 - 2.5 * s4);
  w.qdd[2] = 1 - 9 * s + 18 * s2 - 10 * s3;
  // v1
  w.q[4] = h * (-4 * s3 + 7 * s4 - 3 * s5);
  w.qd[4] = -12 * s2 + 28 * s3 - 15 * s4;
  w.qdd[4] = (-24 * s + 84 * s2 - 60 * s3) / h;
  // a1
  w.q[5] = h2 * (0.5 * s3 - s4 + 0.5 * s5);
  w.qd[5] = h * (1.5 * s2 - 4 * s3 + 2.5 * s4);
  w.qdd[5] = 3 * s - 12 * s2 + 10 * s3;
  return w;
}

}  // namespace idbench::internal
