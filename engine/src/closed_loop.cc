#include "idbench/engine/closed_loop.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "idbench/engine/bullet_simulation.h"
#include "runge_kutta4.h"

namespace idbench {

ClosedLoopLog RunClosedLoop(const Trajectory& reference, double duration, double dt, JointController* controller,
                            const SensorOptions& sensors, const PlantDynamics& plant) {
  const int n_dof = controller->n_dof();
  if (reference.n_dof() != n_dof) {
    throw std::invalid_argument("closed loop: the reference has " + std::to_string(reference.n_dof()) +
                                " joints, the controller " + std::to_string(n_dof));
  }
  SimulationOptions steps_options;
  steps_options.dt = dt;
  steps_options.duration = duration;
  steps_options.tracking_bandwidth = 0.0;
  std::string why;
  if (!steps_options.IsValid(&why)) throw std::invalid_argument("closed loop: " + why);
  if (duration > reference.duration() + 1e-12) {
    throw std::invalid_argument("closed loop: duration " + std::to_string(duration) + " s exceeds the reference's " +
                                std::to_string(reference.duration()) + " s");
  }
  SensorSampler sampler(sensors, n_dof, dt);
  const int n_steps = static_cast<int>(std::lround(duration / dt));
  const int k = sensors.StepsPerSample(dt);
  const int n_samples = (n_steps + k - 1) / k;

  ClosedLoopLog out;
  out.log = sampler.SizedLog(n_samples);
  JointLog& log = out.log;
  out.q_ref.resize(n_samples, n_dof);

  JointState ref(n_dof);
  reference.Evaluate(0.0, &ref);
  Eigen::VectorXd q = ref.q, qd = ref.qd, qdd1(n_dof), tau(n_dof), q_measured(n_dof), tau_logged(n_dof);
  internal::RungeKutta4Workspace stages(n_dof);
  controller->Reset();
  for (int n = 0; n < n_steps; ++n) {
    const double t = n * dt;
    if (n % k == 0) {
      // A sample: measure, command, log; τ is then held to the next sample.
      const int s = n / k;
      reference.Evaluate(t, &ref);
      sampler.MeasureQ(q, q_measured);
      controller->Command(reference, t, q_measured, &tau);
      sampler.MeasureTau(tau, tau_logged);
      plant(q, qd, tau, &qdd1);
      log.t[s] = t;
      log.q.row(s) = q_measured.transpose();
      log.tau.row(s) = tau_logged.transpose();
      out.q_ref.row(s) = ref.q.transpose();
      if (sensors.record_derivatives) {
        log.qd.row(s) = qd.transpose();
        log.qdd.row(s) = qdd1.transpose();
      }
    } else {
      plant(q, qd, tau, &qdd1);
    }
    if (n + 1 == n_steps) break;  // the state after the last step is not logged
    internal::RungeKutta4Step(
        t, dt, qdd1,
        [&](double, const Eigen::VectorXd& q_s, const Eigen::VectorXd& qd_s, Eigen::VectorXd* qdd_s) {
          plant(q_s, qd_s, tau, qdd_s);
        },
        &q, &qd, &stages);
    if (!q.allFinite() || !qd.allFinite()) {
      throw std::runtime_error("closed loop diverged (non-finite state) at t = " + std::to_string(t + dt) +
                               " s; lower the gains or dt");
    }
  }
  return out;
}

ClosedLoopLog SimulateClosedLoop(const RobotModel& model, const Trajectory& reference,
                                 const SimulationOptions& options, const JointControllerOptions& controller_options,
                                 const SensorOptions& sensors) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("simulation options: " + why);
  if (reference.n_dof() != model.n_dof()) {
    throw std::invalid_argument("reference trajectory has " + std::to_string(reference.n_dof()) +
                                " joints, robot '" + model.name() + "' has " + std::to_string(model.n_dof()));
  }
  const int n = model.n_dof();
  const double dt = options.dt;
  JointController controller(controller_options, model, 1.0 / sensors.rate_hz);
  BulletSimulation sim(model, options.feedback);
  Eigen::VectorXd fv(n), fc(n), ia(n);
  for (int j = 0; j < n; ++j) {
    fv[j] = model.link(j).dynamics.viscous;
    fc[j] = model.link(j).dynamics.coulomb;
    ia[j] = model.link(j).dynamics.rotor_inertia;
  }
  const bool has_rotors = (ia.array() != 0.0).any();
  Eigen::VectorXd tau_rigid(n), qdd_free(n);
  Eigen::MatrixXd coupled(n, n), M_inverse(n, n);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(n);
  // Bullet has no rotor inertia: with the rigid bodies' M q̈ + h = τ − Fv q̇ −
  // Fc sign(q̇) − Ia q̈ and Bullet's a(τ') = M⁻¹(τ' − h), q̈ solves
  // (I + M⁻¹ Ia) q̈ = a(τ − Fv q̇ − Fc sign(q̇)), M⁻¹ from the same step's
  // articulated-body factors (BulletSimulation::InverseMassMatrix).
  const PlantDynamics plant = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                                  Eigen::VectorXd* qdd) {
    for (int j = 0; j < n; ++j) tau_rigid[j] = tau[j] - fv[j] * qd[j] - fc[j] * double((qd[j] > 0.0) - (qd[j] < 0.0));
    sim.Accelerations(q, qd, tau_rigid, dt, &qdd_free, /*feedback=*/false);
    if (!has_rotors) {
      *qdd = qdd_free;
      return;
    }
    sim.InverseMassMatrix(&M_inverse);
    coupled.setIdentity();
    for (int j = 0; j < n; ++j) {
      if (ia[j] != 0.0) coupled.col(j) += ia[j] * M_inverse.col(j);
    }
    lu.compute(coupled);
    *qdd = lu.solve(qdd_free);
  };
  return RunClosedLoop(reference, options.duration, dt, &controller, sensors, plant);
}

}  // namespace idbench
