#include "idbench/excitation/sampled_trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "quintic_hermite.h"

namespace idbench {
namespace {

std::string SizeText(const Eigen::MatrixXd& m) { return std::to_string(m.rows()) + "x" + std::to_string(m.cols()); }

// Second derivatives M (n_dof × N) of the natural cubic spline through q at
// times t: for each interior knot i (h_i = t_{i+1} − t_i)
//   h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1} = 6 [(q_{i+1} − q_i)/h_i − (q_i − q_{i−1})/h_{i−1}],
// M_0 = M_{N−1} = 0; solved by the Thomas algorithm (diagonally dominant), all joints at once.
Eigen::MatrixXd NaturalSplineSecondDerivatives(const Eigen::VectorXd& t, const Eigen::MatrixXd& q) {
  const int N = static_cast<int>(t.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(q.rows(), N);
  if (N < 3) return M;
  Eigen::VectorXd upper = Eigen::VectorXd::Zero(N);  // modified super-diagonal
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(q.rows(), N);
  for (int i = 1; i < N - 1; ++i) {
    const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
    const Eigen::VectorXd r = 6.0 * ((q.col(i + 1) - q.col(i)) / h1 - (q.col(i) - q.col(i - 1)) / h0);
    const double lower = i > 1 ? h0 : 0.0;  // M_0 = 0
    const double pivot = 2.0 * (h0 + h1) - lower * upper[i - 1];
    upper[i] = h1 / pivot;
    rhs.col(i) = (r - lower * rhs.col(i - 1)) / pivot;
  }
  for (int i = N - 2; i >= 1; --i) M.col(i) = rhs.col(i) - upper[i] * M.col(i + 1);  // M_{N−1} = 0
  return M;
}

}  // namespace

SampledTrajectory::SampledTrajectory(Eigen::VectorXd t, Eigen::MatrixXd q, Eigen::MatrixXd qd, Eigen::MatrixXd qdd)
    : t_(std::move(t)), q_(std::move(q)), qd_(std::move(qd)), qdd_(std::move(qdd)) {
  const int N = static_cast<int>(t_.size());
  if (N < 2) throw std::invalid_argument("sampled trajectory: expected at least 2 samples, got " + std::to_string(N));
  if (q_.cols() != N || q_.rows() < 1) {
    throw std::invalid_argument("sampled trajectory: expected q of size n_dof x " + std::to_string(N) + ", got " +
                                SizeText(q_));
  }
  const bool derivatives = qd_.size() > 0 || qdd_.size() > 0;
  if (derivatives && (qd_.rows() != q_.rows() || qd_.cols() != N || qdd_.rows() != q_.rows() || qdd_.cols() != N)) {
    throw std::invalid_argument("sampled trajectory: expected qd and qdd of size " + SizeText(q_) + " or both empty, got " +
                                SizeText(qd_) + " and " + SizeText(qdd_));
  }
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(t_[i]) || (i > 0 && !(t_[i] > t_[i - 1]))) {
      throw std::invalid_argument("sampled trajectory: expected strictly increasing finite times, got t[" +
                                  std::to_string(i) + "] = " + std::to_string(t_[i]) +
                                  (i > 0 ? " after " + std::to_string(t_[i - 1]) : std::string()));
    }
  }
  if (!q_.allFinite() || !qd_.allFinite() || !qdd_.allFinite())
    throw std::invalid_argument("sampled trajectory: expected finite q, qd, qdd");
  t_.array() -= t_[0];
  if (derivatives) return;
  // q alone: the natural cubic spline's knot slopes and second derivatives,
  //   qd_i = (q_{i+1} − q_i)/h_i − h_i (2 M_i + M_{i+1})/6  (last knot from the left interval).
  qdd_ = NaturalSplineSecondDerivatives(t_, q_);
  qd_.resize(q_.rows(), N);
  for (int i = 0; i < N - 1; ++i) {
    const double h = t_[i + 1] - t_[i];
    qd_.col(i) = (q_.col(i + 1) - q_.col(i)) / h - h * (2.0 * qdd_.col(i) + qdd_.col(i + 1)) / 6.0;
  }
  const double h = t_[N - 1] - t_[N - 2];
  qd_.col(N - 1) = (q_.col(N - 1) - q_.col(N - 2)) / h + h * (qdd_.col(N - 2) + 2.0 * qdd_.col(N - 1)) / 6.0;
}

void SampledTrajectory::Evaluate(double t, JointState* state) const {
  // The interval [t_i, t_{i+1}] holding t (the end intervals beyond the range).
  const int N = n_samples();
  const int i = std::clamp(static_cast<int>(std::upper_bound(t_.data(), t_.data() + N, t) - t_.data()) - 1, 0, N - 2);
  const internal::QuinticHermiteWeights w = internal::QuinticHermite(t - t_[i], t_[i + 1] - t_[i]);
  const Eigen::MatrixXd* ends[6] = {&q_, &qd_, &qdd_, &q_, &qd_, &qdd_};
  state->q.setZero();
  state->qd.setZero();
  state->qdd.setZero();
  for (int k = 0; k < 6; ++k) {
    const auto knot = ends[k]->col(k < 3 ? i : i + 1);
    state->q += w.q[k] * knot;
    state->qd += w.qd[k] * knot;
    state->qdd += w.qdd[k] * knot;
  }
}

}  // namespace idbench
