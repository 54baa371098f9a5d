// Noise-free joint logs with the features of real ones (jittered time stamps,
// a dropped sample, a payload on the last link), computed from a motion by
// inverse dynamics: the truth that log-reading and identification tests
// compare against.
#pragma once

#include <Eigen/Core>
#include <random>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"

namespace idbench::testing {

// q, qd, qdd of `motion` at the times t, and the motor torque
// τ = InverseDynamics + AddJointDynamicsTorque (rigid body, Fv, Fc, Ia).
inline JointLog SyntheticJointLog(const RobotModel& model, const Trajectory& motion, const Eigen::VectorXd& t) {
  const int n = model.n_dof();
  JointLog log;
  log.t = t;
  log.q.resize(t.size(), n);
  log.qd.resize(t.size(), n);
  log.qdd.resize(t.size(), n);
  log.tau.resize(t.size(), n);
  JointState state(n);
  RobotData data(model);
  for (Eigen::Index s = 0; s < t.size(); ++s) {
    motion.Evaluate(t[s], &state);
    Eigen::VectorXd tau = InverseDynamics(model, state.q, state.qd, state.qdd, &data);
    AddJointDynamicsTorque(model, state.qd, state.qdd, &tau);
    log.q.row(s) = state.q.transpose();
    log.qd.row(s) = state.qd.transpose();
    log.qdd.row(s) = state.qdd.transpose();
    log.tau.row(s) = tau.transpose();
  }
  return log;
}

// Time stamps from 0 to about `duration` [s] as a jittery controller writes
// them: steps of h·(1 + u), u uniform in [−jitter, jitter], with every
// `long_every`-th step `long_factor`·h (a late cycle), and sample `dropped`
// left out (a step of about 2h). Deterministic per seed.
inline Eigen::VectorXd JitteredTimes(double duration, double h, double jitter, int long_every, double long_factor,
                                     int dropped, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<double> t{0.0};
  for (int k = 1; t.back() + 2.0 * h < duration; ++k) {
    const double step = long_every > 0 && k % long_every == 0 ? long_factor * h : h * (1.0 + u(rng));
    t.push_back(t.back() + step);
  }
  if (dropped > 0 && dropped < static_cast<int>(t.size()) - 1) t.erase(t.begin() + dropped);
  return Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
}

// The model with a rigid payload fixed to its last link: mass [kg], centre of
// mass p_BoPcm_B [m] and inertia about it I_Pcm_B [kg m²] in the last link's
// frame, combined with the link's own body (parallel-axis theorem).
inline RobotModel WithPayload(const RobotModel& model, double mass, const Eigen::Vector3d& p_BoPcm_B,
                              const Eigen::Matrix3d& I_Pcm_B) {
  std::vector<Link> links = model.links();
  LinkInertia& link = links.back().inertia;
  const double m = link.mass + mass;
  const Eigen::Vector3d c = (link.mass * link.p_BoBcm_B + mass * p_BoPcm_B) / m;
  auto shifted = [&](double mi, const Eigen::Vector3d& ci, const Eigen::Matrix3d& Ii) {
    const Eigen::Vector3d d = ci - c;
    return Eigen::Matrix3d(Ii + mi * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  link.I_Bcm_B = shifted(link.mass, link.p_BoBcm_B, link.I_Bcm_B) + shifted(mass, p_BoPcm_B, I_Pcm_B);
  link.mass = m;
  link.p_BoBcm_B = c;
  return RobotModel(model.name() + "+payload", std::move(links), model.gravity_W());
}

}  // namespace idbench::testing
