#include "idbench/engine/simulation.h"

#include <cmath>
#include <stdexcept>

#include "idbench/engine/inverse_dynamics.h"
#include "runge_kutta4.h"

namespace idbench {

bool SimulationOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!(dt > 0.0) || !std::isfinite(dt)) return fail("dt: must be > 0 s, got " + std::to_string(dt));
  if (!(duration > 0.0) || !std::isfinite(duration))
    return fail("duration: must be > 0 s, got " + std::to_string(duration));
  if (dt < kMinDt) return fail("dt: must be >= " + std::to_string(kMinDt) + " s");
  if (duration < 2.0 * dt) return fail("duration: must cover at least two steps of `dt`");
  if (duration / dt > kMaxSteps) return fail("duration: more than 1e6 steps of `dt`");
  if (tracking_bandwidth * dt > kMaxBandwidthTimesDt) {
    return fail("dt: must be <= " + std::to_string(kMaxBandwidthTimesDt / tracking_bandwidth) +
                " s for stable tracking at " + std::to_string(tracking_bandwidth) + " rad/s");
  }
  if (!(tracking_bandwidth >= 0.0)) return fail("tracking_bandwidth: must be >= 0");
  return true;
}

int SimulationLog::StepAt(double t) const {
  if (steps.empty() || !std::isfinite(t)) return -1;
  const double n = std::round(t / dt);
  if (n < 0.0 || n >= static_cast<double>(steps.size())) return -1;
  return static_cast<int>(n);
}

SimulationLog Simulate(const RobotModel& model, const Trajectory& reference,
                       const SimulationOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("simulation options: " + why);
  if (reference.n_dof() != model.n_dof()) {
    throw std::invalid_argument("reference trajectory has " + std::to_string(reference.n_dof()) +
                                " joints, robot '" + model.name() + "' has " + std::to_string(model.n_dof()));
  }
  if (options.duration > reference.duration() + 1e-12) {
    throw std::invalid_argument("duration " + std::to_string(options.duration) +
                                " s exceeds the trajectory's " + std::to_string(reference.duration()) + " s");
  }
  const int n_dof = model.n_dof();
  const int n_steps = static_cast<int>(std::lround(options.duration / options.dt));
  const double kp = options.tracking_bandwidth * options.tracking_bandwidth;
  const double kd = 2.0 * options.tracking_bandwidth;
  Eigen::VectorXd q(n_dof), qd(n_dof), tau(n_dof), qdd_cmd(n_dof), qdd1(n_dof);
  internal::RungeKutta4Workspace stages(n_dof);

  // Preallocate the whole log; the loop below does not allocate.
  SimulationLog log;
  log.robot = model.name();
  log.dt = options.dt;
  log.steps.resize(static_cast<size_t>(n_steps));
  for (LogStep& step : log.steps) {
    step.q.resize(n_dof);
    step.qd.resize(n_dof);
    step.qdd.resize(n_dof);
    step.tau.resize(n_dof);
    step.body.resize(static_cast<size_t>(n_dof));
    step.hinge.resize(static_cast<size_t>(n_dof));
  }

  // The motor torque at a state: computed torque along the reference, from
  // the project's own RNEA, evaluated at every stage (a continuous-time law).
  BulletSimulation sim(model, options.feedback);
  RobotData data(model);
  JointState ref(n_dof);
  auto control = [&](double t_s, const Eigen::VectorXd& q_s, const Eigen::VectorXd& qd_s, Eigen::VectorXd* tau_s) {
    reference.Evaluate(t_s, &ref);
    qdd_cmd = ref.qdd + kd * (ref.qd - qd_s) + kp * (ref.q - q_s);
    *tau_s = InverseDynamics(model, q_s, qd_s, qdd_cmd, &data);
  };
  reference.Evaluate(0.0, &ref);
  sim.SetState(ref.q, ref.qd);
  sim.GetState(&q, &qd);

  const double dt = options.dt;
  for (int n = 0; n < n_steps; ++n) {
    LogStep& step = log.steps[static_cast<size_t>(n)];
    step.t = n * dt;
    // Stage 1, at the step's start, is what the log records: the state, the
    // torque, Bullet's acceleration under it and the hinge wrenches, all of
    // this one instant.
    control(step.t, q, qd, &tau);
    sim.Accelerations(q, qd, tau, dt, &qdd1);
    step.q = q;
    step.qd = qd;
    step.qdd = qdd1;
    step.tau = tau;
    step.hinge = sim.joint_feedback();
    // The motor also supplies what joint friction and the rotor consume.
    AddJointDynamicsTorque(model, step.qd, step.qdd, &step.tau);
    // Link kinematics are analytic at the recorded state.
    ComputeKinematics(model, step.q, step.qd, step.qdd, &data);
    for (int i = 0; i < n_dof; ++i) {
      BodySample& body = step.body[static_cast<size_t>(i)];
      body.w_B = BodyAngularVelocity(data, i);
      body.wd_B = BodyAngularAcceleration(data, i);
      body.quaternion = QuaternionRatesFromBodyRates(data.R_WB[static_cast<size_t>(i)], body.w_B, body.wd_B);
      body.a_WBcm_W = data.a_WBcm_W[static_cast<size_t>(i)];
      // Λ and −Λ are the same rotation: keep the logged series continuous.
      if (n > 0 && body.quaternion.lambda.dot(log.steps[static_cast<size_t>(n - 1)].body[static_cast<size_t>(i)]
                                                  .quaternion.lambda) < 0.0) {
        body.quaternion.lambda = -body.quaternion.lambda;
        body.quaternion.lambda_d = -body.quaternion.lambda_d;
        body.quaternion.lambda_dd = -body.quaternion.lambda_dd;
      }
    }
    if (n + 1 == n_steps) break;  // the state after the last step is not logged

    // Stages 2–4, the torque recomputed at each stage's time and state.
    internal::RungeKutta4Step(
        step.t, dt, qdd1,
        [&](double t_s, const Eigen::VectorXd& q_s, const Eigen::VectorXd& qd_s, Eigen::VectorXd* qdd_s) {
          control(t_s, q_s, qd_s, &tau);
          sim.Accelerations(q_s, qd_s, tau, dt, qdd_s, /*feedback=*/false);
        },
        &q, &qd, &stages);
  }
  if (!log.steps.back().q.allFinite() || !log.steps.back().tau.allFinite()) {
    throw std::runtime_error("simulation diverged (non-finite state); reduce dt or the motion's accelerations");
  }
  return log;
}

}  // namespace idbench
