#include "idbench/ident/physically_consistent.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/test_util.h"
#include "ident/joint_torque_experiment.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/linear_estimator.h"

namespace idbench {
namespace {

using testing::RandomVector;
using testing::RelativeError;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The 10 parameters about Bo of a solid box of mass m and edge lengths
// `edges` along the axes of a frame C, R_BC its orientation and c = p_BoBcm_B
// its centroid: I_Bo = R_BC I_C R_BCᵀ + m (cᵀc 𝟙 − c cᵀ).
InertialParameters BoxParameters(double m, const Eigen::Vector3d& edges, const Eigen::Matrix3d& R_BC,
                                 const Eigen::Vector3d& c) {
  const Eigen::Vector3d e2 = edges.cwiseAbs2();
  const Eigen::Matrix3d I_C =
      (m / 12.0) * Eigen::Vector3d(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y()).asDiagonal();
  const Eigen::Matrix3d I =
      R_BC * I_C * R_BC.transpose() + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  InertialParameters pi;
  pi << m, m * c, I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
  return pi;
}

Eigen::Matrix3d SomeRotation() {
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
}

TEST(PseudoInertiaTest, BoxPseudoInertiaIsItsSecondMomentAndPositiveDefinite) {
  const double m = 3.5;
  const Eigen::Vector3d edges(0.4, 0.1, 0.25), c(0.3, -0.2, 0.15);
  const Eigen::Matrix3d R_BC = SomeRotation();
  const InertialParameters pi = BoxParameters(m, edges, R_BC, c);
  // Independent truth: ∫ r rᵀ dm over the box = m (R_BC diag(e²/12) R_BCᵀ + c cᵀ).
  Eigen::Matrix4d J_expected;
  J_expected.topLeftCorner<3, 3>() =
      m * (R_BC * (edges.cwiseAbs2() / 12.0).asDiagonal() * R_BC.transpose() + c * c.transpose());
  J_expected.topRightCorner<3, 1>() = m * c;
  J_expected.bottomLeftCorner<1, 3>() = m * c.transpose();
  J_expected(3, 3) = m;
  const Eigen::Matrix4d J = PseudoInertia(pi);
  EXPECT_LT(RelativeError(J, J_expected), 1e-14);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(J).eigenvalues()[0], 0.0);
  EXPECT_LT(RelativeError(InertialParametersFromPseudoInertia(J), pi), 1e-15);
}

TEST(PseudoInertiaTest, ParametersRoundTripForAnyVector) {
  // The map is linear and invertible on all of ℝ¹⁰, consistent or not.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd pi = RandomVector(10, 2.0, &rng);
    EXPECT_LT(RelativeError(InertialParametersFromPseudoInertia(PseudoInertia(pi)), pi), 4 * kEps);
  }
}

TEST(PseudoInertiaTest, TriangleViolatingInertiaIsNotPositiveSemidefinite) {
  // PUMA 560 link 3 as published: principal moments 0.066, 0.086, 0.0125 kg m²
  // about the centre of mass, 0.066 + 0.0125 < 0.086. J ⪰ 0 ⇔ Σ_cm ⪰ 0, and
  // Σ_cm = ½ tr(I) 𝟙 − I has the eigenvalue (0.066 + 0.0125 − 0.086)/2 = −0.00375.
  const double m = 4.8;
  const Eigen::Vector3d c(-0.0203, -0.0141, 0.070);
  auto body = [&](double Iyy) {
    const Eigen::Matrix3d I = Eigen::Vector3d(0.066, Iyy, 0.0125).asDiagonal();
    const Eigen::Matrix3d I_Bo = I + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    InertialParameters pi;
    pi << m, m * c, I_Bo(0, 0), I_Bo(0, 1), I_Bo(1, 1), I_Bo(0, 2), I_Bo(1, 2), I_Bo(2, 2);
    return pi;
  };
  const InertialParameters puma3 = body(0.086);
  EXPECT_LT(MinPseudoInertiaEigenvalues(puma3, 1)[0], -1e-3);
  for (auto p : {InertiaParameterization::kCholesky, InertiaParameterization::kLogCholesky}) {
    EXPECT_THROW(FactorFromPseudoInertia(p, PseudoInertia(puma3)), std::invalid_argument);
  }
  // On the boundary (Iyy = Ixx + Izz) the smallest eigenvalue is zero.
  EXPECT_NEAR(MinPseudoInertiaEigenvalues(body(0.0785), 1)[0], 0.0, 1e-14);
  // The model file keeps the published values: its link 3 is inconsistent too.
  const Eigen::VectorXd pi_puma = StandardParameters(MakePuma560(), FrictionModel{});
  const Eigen::VectorXd min_eigenvalue = MinPseudoInertiaEigenvalues(pi_puma, 6);
  EXPECT_LT(min_eigenvalue[2], 0.0);
  for (int l : {0, 1, 3, 4, 5}) EXPECT_GT(min_eigenvalue[l], 0.0) << "link " << l + 1;
}

using Parameterization = InertiaParameterization;

std::string ParameterizationName(const ::testing::TestParamInfo<Parameterization>& info) {
  return info.param == Parameterization::kCholesky ? "Cholesky" : "LogCholesky";
}

// Random coordinates; the Cholesky factor's diagonal kept positive, where the
// map is one-to-one.
Eigen::VectorXd RandomFactor(Parameterization p, std::mt19937* rng) {
  Eigen::VectorXd c = RandomVector(10, 1.5, rng);
  if (p == Parameterization::kCholesky) c.head<4>() = c.head<4>().cwiseAbs().array() + 0.1;
  return c;
}

class FactorTest : public ::testing::TestWithParam<Parameterization> {};

TEST_P(FactorTest, CoordinatesRoundTripAndHaveTheirMeaning) {
  const Parameterization p = GetParam();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd c = RandomFactor(p, &rng);
    const InertialParameters pi = InertialParametersFromFactor(p, c);
    // U₃₃ = √m and U₀:₃,₃ = √m · c_cm: m = e^{2α}, c_cm = t (log-Cholesky),
    // m = u44², c_cm = (u14, u24, u34)/u44 (Cholesky).
    const double sqrt_m = p == Parameterization::kLogCholesky ? std::exp(c[0]) : c[0];
    const Eigen::Vector3d c_cm = p == Parameterization::kLogCholesky ? Eigen::Vector3d(c.tail<3>())
                                                                      : Eigen::Vector3d(c.tail<3>() / c[0]);
    EXPECT_NEAR(pi[0], sqrt_m * sqrt_m, 1e-14 * pi[0]);
    EXPECT_LT(RelativeError(pi.segment<3>(1) / pi[0], c_cm), 1e-14);
    EXPECT_GT(MinPseudoInertiaEigenvalues(pi, 1)[0], 0.0);
    EXPECT_LT(RelativeError(FactorFromPseudoInertia(p, PseudoInertia(pi)), c), 1e-12);
  }
  // From a physical body: π → coordinates → π.
  const InertialParameters box = BoxParameters(2.0, Eigen::Vector3d(0.3, 0.05, 0.2), SomeRotation(),
                                               Eigen::Vector3d(0.1, 0.4, -0.3));
  EXPECT_LT(RelativeError(InertialParametersFromFactor(p, FactorFromPseudoInertia(p, PseudoInertia(box))), box),
            1e-14);
}

TEST_P(FactorTest, JacobianMatchesCentralDifferences) {
  const Parameterization p = GetParam();
  std::mt19937 rng(12);
  // h = ε^{1/3}: truncation O(h²) and rounding O(ε/h) balance near ε^{2/3} ≈ 4e-11.
  const double h = std::cbrt(kEps);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd c = RandomFactor(p, &rng);
    FactorJacobian analytic, numeric;
    InertialParametersFromFactor(p, c, &analytic);
    for (int k = 0; k < 10; ++k) {
      Eigen::VectorXd plus = c, minus = c;
      plus[k] += h;
      minus[k] -= h;
      numeric.col(k) = (InertialParametersFromFactor(p, plus) - InertialParametersFromFactor(p, minus)) / (2 * h);
    }
    EXPECT_LT(RelativeError(analytic, numeric), 1e-8);
  }
}

INSTANTIATE_TEST_SUITE_P(Both, FactorTest,
                         ::testing::Values(Parameterization::kCholesky, Parameterization::kLogCholesky),
                         ParameterizationName);

TEST(CholeskyFactorTest, ReachesSingularPseudoInertias) {
  // A zero diagonal entry of U: J ⪰ 0 with a zero eigenvalue, a body of
  // consistent but extreme (here planar) mass distribution — the boundary the
  // log-Cholesky coordinates only approach as d_i → −∞.
  Eigen::VectorXd u(10);
  u << 2.0, 0.5, 0.3, 0.0, 0.1, 0.2, -0.1, 0.4, -0.2, 0.3;
  const InertialParameters pi = InertialParametersFromFactor(Parameterization::kCholesky, u);
  const Eigen::Vector4d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(PseudoInertia(pi)).eigenvalues();
  EXPECT_NEAR(eigenvalues[0], 0.0, 1e-15 * eigenvalues[3]);
  EXPECT_GT(eigenvalues[1], 0.0);
}

// Every link's J ⪰ 0 up to rounding of its largest entries; with a margin,
// J ≻ 0: m > 0 and the inertia about the centre of mass positive definite, as
// a robot file needs.
void ExpectConsistent(const PhysicallyConsistentFit& fit, int n_links, bool with_margin = true) {
  EXPECT_LT(RelativeError(fit.min_pseudo_inertia_eigenvalue, MinPseudoInertiaEigenvalues(fit.pi, n_links)), 1e-15);
  for (int l = 0; l < n_links; ++l) {
    const Eigen::Matrix4d J = PseudoInertia(fit.pi.segment<10>(10 * l));
    EXPECT_GE(fit.min_pseudo_inertia_eigenvalue[l], -1e-12 * J.cwiseAbs().maxCoeff()) << "link " << l + 1;
    if (!with_margin) continue;
    EXPECT_GT(fit.min_pseudo_inertia_eigenvalue[l], 0.0) << "link " << l + 1;
    const double m = J(3, 3);
    ASSERT_GT(m, 0.0) << "link " << l + 1;
    const Eigen::Vector3d c = J.topRightCorner<3, 1>() / m;
    const Eigen::Matrix3d Sigma_cm = J.topLeftCorner<3, 3>() - m * c * c.transpose();
    const Eigen::Matrix3d I_cm = Sigma_cm.trace() * Eigen::Matrix3d::Identity() - Sigma_cm;
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I_cm).eigenvalues()[0], 0.0) << "link " << l + 1;
  }
}

class ObjectiveTest : public ::testing::TestWithParam<Parameterization> {};

TEST_P(ObjectiveTest, GradientMatchesCentralDifferences) {
  const Experiment e = MakeExperiment(true, 50);
  const Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, 20.0), 3);
  // A consistent point off the optimum: boxes of 100…600 kg, friction of
  // both signs; margins of 10⁻³ diag(J) and three squared friction entries.
  std::mt19937 rng(4);
  Eigen::VectorXd pi = e.pi_true;
  pi.tail(12).setLinSpaced(-5.0, 30.0);
  std::vector<Eigen::Matrix4d> margins;
  for (int l = 0; l < 6; ++l) {
    pi.segment<10>(10 * l) = BoxParameters(100.0 * (l + 1), Eigen::Vector3d(0.3, 0.2, 0.4) + RandomVector(3, 0.1, &rng),
                                           SomeRotation(), RandomVector(3, 0.5, &rng));
    margins.push_back(1e-3 * Eigen::Matrix4d(PseudoInertia(pi.segment<10>(10 * l)).diagonal().asDiagonal()));
  }
  const std::vector<int> nonnegative{62, 65, 71};
  PhysicallyConsistentObjective objective(CombinedFactor(e.W, tau), e.base, 6, GetParam(), margins, nonnegative);
  const Eigen::VectorXd x = objective.VariablesAt(pi);
  for (int k : nonnegative) EXPECT_NEAR(x[k] * x[k], pi[k], 1e-14 * pi[k]);
  EXPECT_LT(RelativeError(objective.StandardParametersAt(x), pi), 1e-12);
  // The factor form of the cost equals the cost on all rows.
  Eigen::VectorXd gradient;
  const double f = objective.Evaluate(x, &gradient);
  EXPECT_NEAR(f, (e.W * e.base.combination * pi - tau).squaredNorm(), 1e-12 * f);
  EXPECT_NEAR(f, objective.Residual(x).squaredNorm() + objective.residual_floor(), 1e-14 * f);
  EXPECT_LT(RelativeError(gradient, 2.0 * objective.ResidualJacobian(x).transpose() * objective.Residual(x)), 1e-12);
  // h = ε^{1/3} max(1, |x_k|): central-difference error O(h²) + O(ε f/h).
  Eigen::VectorXd numeric(x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double h = std::cbrt(kEps) * std::max(1.0, std::abs(x[k]));
    Eigen::VectorXd plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    numeric[k] = (objective.Evaluate(plus) - objective.Evaluate(minus)) / (2 * h);
  }
  EXPECT_LT(RelativeError(gradient, numeric), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Both, ObjectiveTest,
                         ::testing::Values(Parameterization::kCholesky, Parameterization::kLogCholesky),
                         ParameterizationName);

PhysicallyConsistentOptions OptionsFor(Parameterization p, double margin = PhysicallyConsistentOptions{}.pseudo_inertia_margin) {
  PhysicallyConsistentOptions options;
  options.parameterization = p;
  options.pseudo_inertia_margin = margin;
  return options;
}

class NoiseFreeTest : public ::testing::TestWithParam<bool> {};

// From no prior at all (π_prior = 0), whose nearest standard parameters are
// far from consistent, the fit recovers the true base parameters.
TEST_P(NoiseFreeTest, RecoversTheTrueBaseParameters) {
  const Experiment e = MakeExperiment(GetParam(), 200);
  const Eigen::VectorXd beta_ols = SolveOls(e.W, e.tau, 6).beta;
  const Eigen::VectorXd prior = Eigen::VectorXd::Zero(e.pi_true.size());
  EXPECT_LT(MinPseudoInertiaEigenvalues(ClosestStandardParameters(e.base, beta_ols, prior), 6).minCoeff(), 0.0);
  const PhysicallyConsistentFit fit =
      SolvePhysicallyConsistent(CombinedFactor(e.W, e.tau), e.base, 6, beta_ols, prior);
  EXPECT_LT((fit.beta - e.beta_true).norm() / e.beta_true.norm(), 1e-6) << fit.status;
  EXPECT_TRUE(fit.converged) << fit.status;
  ExpectConsistent(fit, 6);
}

INSTANTIATE_TEST_SUITE_P(Friction, NoiseFreeTest, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "FvFc" : "None"; });

class NoisyTest : public ::testing::TestWithParam<Parameterization> {};

// Gaussian torque noise (σ 50 N m on joints 1–3, 5 N m on 4–6; torques reach
// ~10⁴ N m), the robot file as prior.
TEST_P(NoisyTest, CostsLittleMoreThanOlsAndEveryLinkIsConsistent) {
  const Experiment e = MakeExperiment(true, 200);
  const Eigen::VectorXd sigma = (Eigen::VectorXd(6) << 50, 50, 50, 5, 5, 5).finished();
  const Eigen::VectorXd tau = AddNoise(e.tau, sigma, 2024);
  const Eigen::VectorXd beta_ols = SolveOls(e.W, tau, 6).beta;
  const PhysicallyConsistentFit fit =
      SolvePhysicallyConsistent(CombinedFactor(e.W, tau), e.base, 6, beta_ols, e.pi_true, OptionsFor(GetParam()));
  EXPECT_GE(fit.cost, fit.ols_cost * (1 - 1e-12));
  EXPECT_LE(fit.cost, 1.05 * fit.ols_cost) << fit.status;
  ExpectConsistent(fit, 6);
}

INSTANTIATE_TEST_SUITE_P(Both, NoisyTest,
                         ::testing::Values(Parameterization::kCholesky, Parameterization::kLogCholesky),
                         ParameterizationName);

struct InconsistentCase {
  Parameterization parameterization;
  double margin;
  // Least start cost / cost. The log-Cholesky search stalls on this boundary
  // optimum (physically_consistent.h), where depends on rounding: 143× and 36×
  // for two factors of [W τ] equal up to rounding.
  double min_improvement;
};

class InconsistentOlsTest : public ::testing::TestWithParam<InconsistentCase> {};

TEST_P(InconsistentOlsTest, EndsConsistent) {
  // 40 samples and σ = 400 N m: the standard parameters nearest the true ones
  // that reproduce the OLS estimate have links with J ⋡ 0.
  const Experiment e = MakeExperiment(false, 40);
  const Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, 400.0), 99);
  const Eigen::VectorXd beta_ols = SolveOls(e.W, tau, 6).beta;
  const Eigen::VectorXd pi_ols = ClosestStandardParameters(e.base, beta_ols, e.pi_true);
  EXPECT_LT((e.base.combination * pi_ols - beta_ols).norm(), 1e-10 * beta_ols.norm());
  EXPECT_LT(MinPseudoInertiaEigenvalues(pi_ols, 6).minCoeff(), 0.0);
  const auto [parameterization, margin, min_improvement] = GetParam();
  const PhysicallyConsistentFit fit = SolvePhysicallyConsistent(CombinedFactor(e.W, tau), e.base, 6, beta_ols,
                                                                e.pi_true, OptionsFor(parameterization, margin));
  ExpectConsistent(fit, 6, margin > 0.0);
  // The constraint is active (no consistent π reaches the OLS cost), and the
  // search improved on its start by orders of magnitude.
  EXPECT_GT(fit.cost, 1.01 * fit.ols_cost);
  EXPECT_LT(fit.cost, fit.start_cost / min_improvement) << fit.status;
}

INSTANTIATE_TEST_SUITE_P(Cases, InconsistentOlsTest,
                         ::testing::Values(InconsistentCase{Parameterization::kCholesky, 1e-7, 100.0},
                                           InconsistentCase{Parameterization::kCholesky, 0.0, 100.0},
                                           InconsistentCase{Parameterization::kLogCholesky, 1e-7, 20.0}),
                         [](const auto& info) {
                           return std::string(info.param.parameterization == Parameterization::kCholesky
                                                  ? "Cholesky"
                                                  : "LogCholesky") +
                                  (info.param.margin > 0.0 ? "_Margin" : "_NoMargin");
                         });

// Small true friction (Fv, Fc ~ 0.2…0.45) under heavy noise: OLS finds some
// negative, which a robot file cannot hold; listed as nonnegative they end ≥ 0.
TEST(PhysicallyConsistentTest, NonnegativeFrictionEndsNonnegative) {
  const Experiment e = MakeExperiment(true, 40, 0.01);
  const Eigen::VectorXd tau = AddNoise(e.tau, Eigen::VectorXd::Constant(6, 50.0), 5);
  const Eigen::VectorXd beta_ols = SolveOls(e.W, tau, 6).beta;
  const Eigen::VectorXd pi_ols = ClosestStandardParameters(e.base, beta_ols, e.pi_true);
  EXPECT_LT(pi_ols.tail(12).minCoeff(), 0.0);
  PhysicallyConsistentOptions options;
  for (int k = 60; k < 72; ++k) options.nonnegative.push_back(k);
  const PhysicallyConsistentFit fit =
      SolvePhysicallyConsistent(CombinedFactor(e.W, tau), e.base, 6, beta_ols, e.pi_true, options);
  EXPECT_GE(fit.pi.tail(12).minCoeff(), 0.0);
  ExpectConsistent(fit, 6);
  EXPECT_GE(fit.cost, fit.ols_cost);
  EXPECT_LT(fit.cost, fit.start_cost);
}

TEST(PhysicallyConsistentTest, RejectsBadInput) {
  const Experiment e = MakeExperiment(false, 20);
  const Eigen::VectorXd beta = SolveOls(e.W, e.tau, 6).beta;
  const Eigen::MatrixXd factor = CombinedFactor(e.W, e.tau);
  PhysicallyConsistentOptions options;
  options.max_evaluations = 0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("max_evaluations"), std::string::npos);
  EXPECT_THROW(SolvePhysicallyConsistent(factor, e.base, 6, beta, e.pi_true, options), std::invalid_argument);
  EXPECT_THROW(CombinedFactor(e.W, e.tau.head(6)), std::invalid_argument);
  EXPECT_THROW(SolvePhysicallyConsistent(factor.topLeftCorner(5, 5), e.base, 6, beta, e.pi_true),
               std::invalid_argument);
  EXPECT_THROW(SolvePhysicallyConsistent(factor, e.base, 7, beta, e.pi_true), std::invalid_argument);
  EXPECT_THROW(SolvePhysicallyConsistent(factor, e.base, 6, beta.head(3), e.pi_true), std::invalid_argument);
  EXPECT_THROW(SolvePhysicallyConsistent(factor, e.base, 6, beta, e.pi_true.head(10)), std::invalid_argument);
  options = {};
  options.nonnegative = {3};  // an inertial parameter, not friction
  EXPECT_THROW(SolvePhysicallyConsistent(factor, e.base, 6, beta, e.pi_true, options), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
