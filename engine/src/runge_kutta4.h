// The classical fourth-order Runge–Kutta step on a mechanism's state
// x = (q, qd), ẋ = (qd, qdd(t, q, qd)): the integrator of the open-loop
// simulation (simulation.cc) and of the closed loop (closed_loop.cc).
#pragma once

#include <Eigen/Core>

namespace idbench::internal {

// Stage states and accelerations, sized once so that a step does not allocate.
struct RungeKutta4Workspace {
  Eigen::VectorXd q2, qd2, qdd2, q3, qd3, qdd3, q4, qd4, qdd4;
  explicit RungeKutta4Workspace(int n_dof)
      : q2(n_dof), qd2(n_dof), qdd2(n_dof), q3(n_dof), qd3(n_dof), qdd3(n_dof), q4(n_dof), qd4(n_dof),
        qdd4(n_dof) {}
};

// Advances (*q, *qd) from t to t + dt (Hairer, Nørsett & Wanner, Solving
// ODEs I, §II.1). qdd1 is the first stage's acceleration at (t, *q, *qd),
// which the caller has computed (and logged); `acceleration(t_s, q_s, qd_s,
// &qdd_s)` gives stages 2–4.
template <typename Acceleration>
void RungeKutta4Step(double t, double dt, const Eigen::VectorXd& qdd1, Acceleration&& acceleration,
                     Eigen::VectorXd* q, Eigen::VectorXd* qd, RungeKutta4Workspace* w) {
  w->q2 = *q + 0.5 * dt * *qd;
  w->qd2 = *qd + 0.5 * dt * qdd1;
  acceleration(t + 0.5 * dt, w->q2, w->qd2, &w->qdd2);
  w->q3 = *q + 0.5 * dt * w->qd2;
  w->qd3 = *qd + 0.5 * dt * w->qdd2;
  acceleration(t + 0.5 * dt, w->q3, w->qd3, &w->qdd3);
  w->q4 = *q + dt * w->qd3;
  w->qd4 = *qd + dt * w->qdd3;
  acceleration(t + dt, w->q4, w->qd4, &w->qdd4);
  *q += dt / 6.0 * (*qd + 2.0 * w->qd2 + 2.0 * w->qd3 + w->qd4);
  *qd += dt / 6.0 * (qdd1 + 2.0 * w->qdd2 + 2.0 * w->qdd3 + w->qdd4);
}

}  // namespace idbench::internal
