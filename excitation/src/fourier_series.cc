#include "idbench/excitation/fourier_series.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace idbench {

FourierSeriesTrajectory::FourierSeriesTrajectory(Eigen::VectorXd q0, Eigen::MatrixXd a, Eigen::MatrixXd b,
                                                 double f0, double duration)
    : q0_(std::move(q0)), a_(std::move(a)), b_(std::move(b)), f0_(f0), duration_(duration) {
  if (a_.rows() != q0_.size() || b_.rows() != q0_.size() || a_.cols() != b_.cols() || a_.cols() < 1) {
    throw std::invalid_argument("Fourier series: expected a and b of size " + std::to_string(q0_.size()) +
                                " x H (H >= 1), got " + std::to_string(a_.rows()) + "x" +
                                std::to_string(a_.cols()) + " and " + std::to_string(b_.rows()) + "x" +
                                std::to_string(b_.cols()));
  }
  if (!(f0_ > 0.0)) throw std::invalid_argument("Fourier series: f0 must be > 0");
  if (!(duration_ > 0.0)) throw std::invalid_argument("Fourier series: duration must be > 0");
}

void FourierSeriesTrajectory::Evaluate(double t, JointState* state) const {
  const double wf = 2.0 * std::numbers::pi * f0_;
  state->q = q0_;
  state->qd.setZero();
  state->qdd.setZero();
  for (int l = 1; l <= harmonics(); ++l) {
    const double w = wf * l;
    const double s = std::sin(w * t), c = std::cos(w * t);
    state->q += (a_.col(l - 1) * s - b_.col(l - 1) * c) / w;
    state->qd += a_.col(l - 1) * c + b_.col(l - 1) * s;
    state->qdd += (-a_.col(l - 1) * s + b_.col(l - 1) * c) * w;
  }
}

}  // namespace idbench
