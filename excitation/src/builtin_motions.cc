#include "idbench/excitation/builtin_motions.h"

#include "idbench/excitation/constant_acceleration.h"
#include "idbench/excitation/fourier_series.h"

#include <algorithm>
#include <numbers>
#include <stdexcept>

namespace idbench {

std::unique_ptr<Trajectory> MakePaperMotion(int n_dof, double qdd, double duration) {
  Eigen::VectorXd accel = Eigen::VectorXd::Zero(n_dof);
  accel.head(std::min(n_dof, 2)).setConstant(qdd);
  return std::make_unique<ConstantAccelerationTrajectory>(Eigen::VectorXd::Zero(n_dof),
                                                          Eigen::VectorXd::Zero(n_dof), accel, duration);
}

std::unique_ptr<Trajectory> MakeGeneralMotion(int n_dof, double duration) {
  constexpr double kF0 = 0.5;  // [Hz]
  Eigen::MatrixXd a(n_dof, 2), b(n_dof, 2);
  for (int j = 0; j < n_dof; ++j) {
    a(j, 0) = 0.6 - 0.05 * j;  // [rad/s]
    a(j, 1) = 0.25 * ((j % 2) ? -1.0 : 1.0);
    b(j, 0) = 0.3 + 0.04 * j;
    b(j, 1) = -0.15 + 0.03 * j;
  }
  // Offsets chosen so that q(0) = 0: q(0) = q0 − Σ b_l/(ω_f l).
  const double wf = 2.0 * std::numbers::pi * kF0;
  const Eigen::VectorXd q0 = b.col(0) / wf + b.col(1) / (2.0 * wf);
  return std::make_unique<FourierSeriesTrajectory>(q0, a, b, kF0, duration);
}

void ReversedTrajectory::Evaluate(double t, JointState* state) const {
  forward_->Evaluate(duration() - t, state);
  state->qd = -state->qd;
}

std::vector<std::string> BuiltinMotionNames() { return {"paper", "general", "general-reversed"}; }

std::unique_ptr<Trajectory> MakeBuiltinMotion(const std::string& name, int n_dof, double duration,
                                              double paper_qdd) {
  if (name == "paper") return MakePaperMotion(n_dof, paper_qdd, duration);
  if (name == "general") return MakeGeneralMotion(n_dof, duration);
  if (name == "general-reversed") return std::make_unique<ReversedTrajectory>(MakeGeneralMotion(n_dof, duration));
  std::string names;
  for (const std::string& n : BuiltinMotionNames()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("trajectory '" + name + "': not a built-in motion (" + names + ")");
}

}  // namespace idbench
