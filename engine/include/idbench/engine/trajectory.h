// A joint-space motion: q, qd, qdd given analytically at any time t.
// Families (constant acceleration, Fourier series, sampled CSV) live in the
// excitation module; the simulation only needs this interface.
#pragma once

#include <Eigen/Core>

namespace idbench {

struct JointState {
  Eigen::VectorXd q;    // joint positions [rad] (n_dof)
  Eigen::VectorXd qd;   // joint velocities [rad/s] (n_dof)
  Eigen::VectorXd qdd;  // joint accelerations [rad/s²] (n_dof)

  explicit JointState(int n_dof = 0)
      : q(Eigen::VectorXd::Zero(n_dof)), qd(Eigen::VectorXd::Zero(n_dof)), qdd(Eigen::VectorXd::Zero(n_dof)) {}
};

class Trajectory {
 public:
  virtual ~Trajectory() = default;
  virtual int n_dof() const = 0;
  virtual double duration() const = 0;  // [s]; defined on [0, duration]
  // Writes q, qd, qdd at time t into *state (already sized n_dof).
  virtual void Evaluate(double t, JointState* state) const = 0;

  JointState At(double t) const {
    JointState state(n_dof());
    Evaluate(t, &state);
    return state;
  }
};

}  // namespace idbench
