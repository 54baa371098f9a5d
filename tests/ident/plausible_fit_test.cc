#include "idbench/ident/plausible_fit.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <algorithm>
#include <cstdio>

#include "ident/dsdp_problem.h"
#include "ident/joint_torque_experiment.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/linear_estimator.h"
#include "plausible_program.h"

namespace idbench {
namespace {

// The prior: every link's 10 parameters times `inertial_factor` (the same
// body, heavier: still physical), friction times `friction_factor`.
Eigen::VectorXd ScaledPrior(const Experiment& e, double inertial_factor, double friction_factor) {
  Eigen::VectorXd prior = e.pi_true;
  const Eigen::Index n_inertial = 10 * e.model.n_links();
  prior.head(n_inertial) *= inertial_factor;
  prior.tail(prior.size() - n_inertial) *= friction_factor;
  return prior;
}

// Options for a prior the way identify builds them (robot file = prior).
PlausibleFitOptions OptionsForPrior(const Experiment& e, const Eigen::VectorXd& prior) {
  return MakePlausibleFitOptions(ModelWithStandardParameters(e.model, e.friction, prior), e.friction,
                                 PlausibilitySettings{});
}

// Noise-free data from paper6r with friction, prior 20 % heavier and half the
// friction: the data determine β, and the fit finds it although the prior
// disagrees; the standard parameters no base parameter contains (the
// directions no data reach) stay exactly at the prior.
TEST(PlausibleFitTest, NoiseFreeDataOverrideAWrongPriorWhereTheyReach) {
  const Experiment e = MakeExperiment(true, 200);
  const Eigen::VectorXd prior = ScaledPrior(e, 1.2, 0.5);
  const PhysicallyConsistentFit fit =
      SolvePlausibleFit(CombinedFactor(e.W, e.tau), e.base, 6, prior, OptionsForPrior(e, prior));
  ASSERT_TRUE(fit.converged) << fit.status;
  EXPECT_LE(fit.duality_gap, 1e-9);
  EXPECT_LT((fit.beta - e.beta_true).norm(), 1e-7 * e.beta_true.norm());
  EXPECT_GE(fit.min_pseudo_inertia_eigenvalue.minCoeff(), 0.0);
  ASSERT_FALSE(e.base.unexcited.empty());
  for (int k : e.base.unexcited)
    EXPECT_NEAR(fit.pi[k], prior[k], 1e-9 * std::max(1.0, std::abs(prior[k]))) << "standard parameter " << k;
}

// The PUMA 560 with its published friction (scaled), torque noise 0.5 N m
// (joints 1–3) and 0.05 N m (4–6): the noise pushes several of the weakly
// excited wrist masses against their bounds. DSDP (dual scaling on the
// epigraph LMI, a different algorithm) solves the same program to the same
// optimum; ours is certified, so it is never above DSDP's.
TEST(PlausibleFitTest, ActiveBoundsAndTheOptimumAgreesWithDsdp) {
  const Experiment e = MakeExperiment(true, 400, 0.05, MakePuma560());
  const Eigen::VectorXd tau = AddNoise(e.tau, (Eigen::VectorXd(6) << 0.5, 0.5, 0.5, 0.05, 0.05, 0.05).finished(), 11);
  const Eigen::MatrixXd factor = CombinedFactor(e.W, tau);
  const PlausibleFitOptions options = OptionsForPrior(e, e.pi_true);
  const PhysicallyConsistentFit fit = SolvePlausibleFit(factor, e.base, 6, e.pi_true, options);
  ASSERT_TRUE(fit.converged) << fit.status;
  EXPECT_LE(fit.duality_gap, 1e-9);
  EXPECT_FALSE(fit.active_bounds.empty());
  const internal::PlausibleProgram program = internal::MakePlausibleProgram(factor, e.base, 6, e.pi_true, options);
  Eigen::VectorXd u;
  const test::SdpSolution dsdp = test::SolveWithDsdp(program.sdp, &u);
  ASSERT_TRUE(dsdp.feasible) << dsdp.status;
  const Eigen::VectorXd u_ours = (fit.pi - e.pi_true).cwiseQuotient(program.D);
  auto objective = [&](const Eigen::VectorXd& v) { return (program.sdp.R * v - program.sdp.z).squaredNorm(); };
  const double offset = program.rest + program.rho2 / program.s2;
  const double ours = objective(u_ours) + offset, theirs = objective(u) + offset;
  EXPECT_LE(ours, theirs * (1 + 1e-8));
  EXPECT_NEAR(ours, theirs, 1e-6 * theirs);
  EXPECT_LT((fit.pi - (e.pi_true + program.D.cwiseProduct(u))).norm(), 1e-3 * fit.pi.norm());
}

}  // namespace
}  // namespace idbench
