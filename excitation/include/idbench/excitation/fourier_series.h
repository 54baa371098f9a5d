// Finite Fourier series per joint (Swevers et al. 1997):
//   q_j(t) = q0_j + Σ_{l=1..H} [ a_jl/(ω_f l) sin(ω_f l t) − b_jl/(ω_f l) cos(ω_f l t) ],
// ω_f = 2π f0. Derivatives are analytic; the motion is periodic with 1/f0.
#pragma once

#include "idbench/engine/trajectory.h"

namespace idbench {

class FourierSeriesTrajectory final : public Trajectory {
 public:
  // a, b: n_dof × H coefficient matrices [rad/s]; q0: offsets [rad];
  // f0 > 0 [Hz]; duration > 0 [s]. Throws std::invalid_argument otherwise.
  FourierSeriesTrajectory(Eigen::VectorXd q0, Eigen::MatrixXd a, Eigen::MatrixXd b, double f0,
                          double duration);

  int n_dof() const override { return static_cast<int>(q0_.size()); }
  int harmonics() const { return static_cast<int>(a_.cols()); }
  double f0() const { return f0_; }
  double duration() const override { return duration_; }
  void Evaluate(double t, JointState* state) const override;

 private:
  Eigen::VectorXd q0_;
  Eigen::MatrixXd a_, b_;
  double f0_, duration_;
};

}  // namespace idbench
