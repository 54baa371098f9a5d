// Finite Fourier series per joint (Swevers et al. 1997):
//   q_j(t) = q0_j + Σ_{l=1..H} [ a_jl/(ω_f l) sin(ω_f l t) − b_jl/(ω_f l) cos(ω_f l t) ] + p_j(t),
// ω_f = 2π f0. Derivatives are analytic. Without the rest-to-rest part (p = 0)
// the motion is periodic with 1/f0.
//
// Rest-to-rest: p_j is the quintic that brings the motion to rest at both ends
// and back to its start pose: with f_j the Fourier sum (the bracket above),
//   p(0) = 0, p(T) = f(0) − f(T), p'(0) = −f'(0), p'(T) = −f'(T), p''(0) = −f''(0), p''(T) = −f''(T),
// so qd = qdd = 0 at t = 0 and t = T = duration, and q(0) = q(T) = q0 + f(0).
// (When T is a whole number of periods, f(T) = f(0) and p(T) = 0.)
//
// Either way q, qd, qdd are linear in the coefficients a, b (BasisAt): that is
// what the excitation design differentiates.
#pragma once

#include "idbench/engine/trajectory.h"

namespace idbench {

// Weights w (each of length 2H, order [a_1..a_H, b_1..b_H]) such that for every joint j
//   q_j(t) = q0_j + w.q · [a_j1..a_jH, b_j1..b_jH],  qd_j(t) = w.qd · [...],  qdd_j(t) = w.qdd · [...].
struct FourierBasis {
  Eigen::VectorXd q;    // [s] (2H)
  Eigen::VectorXd qd;   // [1] (2H)
  Eigen::VectorXd qdd;  // [1/s] (2H)
};

class FourierSeriesTrajectory final : public Trajectory {
 public:
  // The most harmonics `design` searches and a trajectory file may hold: every
  // evaluation costs O(H·n), and a log is evaluated at every step.
  static constexpr int kMaxHarmonics = 50;

  // a, b: n_dof × H coefficient matrices [rad/s]; q0: offsets [rad];
  // f0 > 0 [Hz]; duration > 0 [s]; rest_to_rest adds the quintic above.
  // Throws std::invalid_argument otherwise.
  FourierSeriesTrajectory(Eigen::VectorXd q0, Eigen::MatrixXd a, Eigen::MatrixXd b, double f0, double duration,
                          bool rest_to_rest = false);

  int n_dof() const override { return static_cast<int>(q0_.size()); }
  int harmonics() const { return static_cast<int>(a_.cols()); }
  double f0() const { return f0_; }
  double duration() const override { return duration_; }
  bool rest_to_rest() const { return rest_to_rest_; }
  const Eigen::VectorXd& q0() const { return q0_; }  // [rad] (n_dof)
  const Eigen::MatrixXd& a() const { return a_; }    // [rad/s] (n_dof × H)
  const Eigen::MatrixXd& b() const { return b_; }    // [rad/s] (n_dof × H)
  void Evaluate(double t, JointState* state) const override;

  // The weights at time t [s] of a series with base frequency f0 > 0 [Hz],
  // harmonics H >= 1 and duration > 0 [s] (used only when rest_to_rest).
  // Evaluate uses exactly these weights.
  static FourierBasis BasisAt(double t, double f0, int harmonics, double duration, bool rest_to_rest);
  // The same into *basis, which is resized to 2H if needed (no allocation when
  // already that size: for hot loops).
  static void BasisAt(double t, double f0, int harmonics, double duration, bool rest_to_rest, FourierBasis* basis);

 private:
  Eigen::VectorXd q0_;
  Eigen::MatrixXd a_, b_;
  double f0_, duration_;
  bool rest_to_rest_;
};

}  // namespace idbench
