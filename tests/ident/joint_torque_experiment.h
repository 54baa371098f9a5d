// A joint-torque identification experiment with a known truth, shared by the
// physically consistent estimators' tests.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

// Base regressor and torques of paper6r on the general Fourier motion, sampled
// analytically; torques from the Newton–Euler inverse dynamics plus friction.
struct Experiment {
  RobotModel model = MakePaper6r();
  FrictionModel friction;
  BaseParameters base;
  Eigen::MatrixXd W;       // base regressor (6 n_samples × n_base)
  Eigen::VectorXd tau;     // [N m] (6 n_samples)
  Eigen::VectorXd pi_true; // standard parameters, friction included
  Eigen::VectorXd beta_true;
};

// Fv, Fc of joint j: (20 + 5j, 40 − 4j) × friction_scale [N m s/rad, N m].
inline Experiment MakeExperiment(bool with_friction, int n_samples, double friction_scale = 1.0,
                                 const RobotModel& model = MakePaper6r()) {
  const double duration = 4.0;
  Experiment e;
  e.model = model;
  if (with_friction) {
    e.friction.viscous = e.friction.coulomb = true;
    std::vector<Link> links = e.model.links();
    for (int j = 0; j < 6; ++j) {
      links[static_cast<size_t>(j)].dynamics.viscous = (20.0 + 5.0 * j) * friction_scale;
      links[static_cast<size_t>(j)].dynamics.coulomb = (40.0 - 4.0 * j) * friction_scale;
    }
    e.model = RobotModel(e.model.name(), links, e.model.gravity_W());
  }
  e.base = ComputeBaseParameters(e.model, e.friction);
  e.pi_true = StandardParameters(e.model, e.friction);
  e.beta_true = e.base.combination * e.pi_true;
  const auto motion = MakeGeneralMotion(6, duration);
  e.W.resize(6 * n_samples, e.base.n_base());
  e.tau.resize(6 * n_samples);
  RobotData d(e.model);
  Eigen::MatrixXd Y;
  for (int s = 0; s < n_samples; ++s) {
    const JointState x = motion->At(duration * (s + 0.5) / n_samples);
    ComputeJointTorqueRegressor(e.model, e.friction, x.q, x.qd, x.qdd, &d, &Y);
    e.W.middleRows(6 * s, 6) = e.base.Reduce(Y);
    Eigen::VectorXd tau = InverseDynamics(e.model, x.q, x.qd, x.qdd, &d);
    AddJointDynamicsTorque(e.model, x.qd, x.qdd, &tau);
    e.tau.segment(6 * s, 6) = tau;
  }
  return e;
}

// Adds N(0, σ_j²) to joint j's rows.
inline Eigen::VectorXd AddNoise(const Eigen::VectorXd& tau, const Eigen::VectorXd& sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd noisy = tau;
  for (Eigen::Index r = 0; r < tau.size(); ++r) noisy[r] += sigma[r % sigma.size()] * normal(rng);
  return noisy;
}

}  // namespace idbench
