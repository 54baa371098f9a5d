#include "idbench/ident/log_identification.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/prepared_log_equations.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

// Two puma560 logs of the general motion (t, q, qd, qdd, τ at 200 Hz, τ with
// white noise), prepared as recorded (no filter).
class LogIdentificationTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePuma560();
  // The log's own terms (SyntheticJointLog: rigid body, Fv, Fc, Ia).
  JointTorqueOptions options_ = [] {
    JointTorqueOptions options;
    options.friction = {.viscous = true, .coulomb = true, .rotor_inertia = true};
    return options;
  }();

  PreparedLog Log(double t0, double duration, unsigned seed, const std::string& name) const {
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 20.0});
    const Eigen::Index n = static_cast<Eigen::Index>(duration * 200.0) + 1;
    RecordedJointLog recorded;
    recorded.log = testing::SyntheticJointLog(model_, *motion, Eigen::VectorXd::LinSpaced(n, t0, t0 + duration));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.2);
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < 6; ++j) recorded.log.tau(s, j) += noise(rng);
    }
    recorded.lines.resize(static_cast<size_t>(n));
    for (Eigen::Index s = 0; s < n; ++s) recorded.lines[static_cast<size_t>(s)] = static_cast<int>(s) + 2;
    return PrepareRecordedJointLog(std::move(recorded), name, {});
  }
};

// Two logs identified together: β equals OLS on the two logs' equations
// stacked densely (FactorStackedEquations on each, merged, solved), each log's
// own cond is its own fold's, and the stages are announced in order.
TEST_F(LogIdentificationTest, SeveralLogsGiveTheStackedLeastSquaresFit) {
  const PreparedLog a = Log(0.0, 6.0, 1, "a.csv"), b = Log(9.0, 5.0, 2, "b.csv");
  std::vector<std::string> stages;
  const LogIdentification identified =
      IdentifyFromLogs(model_, {&a, &b}, options_, nullptr, [&](const std::string& stage) -> const StreamObserver* {
        stages.push_back(stage);
        return nullptr;
      });
  const BaseParameters& base = identified.identification.base;
  StackedFactors own_a = FactorStackedEquations(model_, options_.friction, base, a.log);
  const StackedFactors own_b = FactorStackedEquations(model_, options_.friction, base, b.log);
  const double cond_a = SolveOls(own_a).cond;
  MergeStackedFactors(own_b, &own_a);
  const LinearFit stacked = SolveOls(own_a);
  EXPECT_LT((identified.identification.beta - stacked.beta).norm(), 1e-10 * stacked.beta.norm());
  ASSERT_EQ(identified.n_kept, (std::vector<Eigen::Index>{1201, 1001}));
  ASSERT_EQ(identified.cond.size(), 2u);
  EXPECT_NEAR(identified.cond[0], cond_a, 1e-9 * cond_a);
  // The noise is 0.2 N m on every joint: β within a few σ of the file's.
  const Eigen::VectorXd error = identified.identification.beta - identified.identification.beta_model;
  for (int k = 0; k < base.n_base(); ++k) {
    if (!identified.identification.linear.identifiable[static_cast<size_t>(k)]) continue;
    EXPECT_LT(std::abs(error[k]), 5.0 * identified.identification.linear.sigma[k]) << base.names[static_cast<size_t>(k)];
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"identifying from a.csv", "identifying from b.csv", "solving (ols)",
                                              "sigma from the residual of a.csv", "sigma from the residual of b.csv"}));
}

// The consistent estimate centred on another estimate (what a closed-loop
// estimator's model is taken from): centred on least squares' own β it is the
// ordinary consistent fit (the same objective, ‖R β − z‖² + ρ²); centred half
// way to the truth, its β follows the centre (in the data's metric ‖R·‖), and
// its verdict judges the cost against the centre's own residual.
TEST_F(LogIdentificationTest, ConsistentFitCentredOnAnotherEstimate) {
  const PreparedLog a = Log(0.0, 6.0, 1, "a.csv");
  const LogIdentification identified = IdentifyFromLogs(model_, {&a}, options_);
  const JointTorqueIdentification& ols = identified.identification;
  JointTorqueIdentification centred = ols;
  ASSERT_NO_THROW(CentreConsistentFit(model_, identified.factors, options_, ols.linear.beta, &centred));
  EXPECT_LT((centred.consistent.beta - ols.consistent.beta).norm(), 1e-6 * ols.consistent.beta.norm());
  EXPECT_NEAR(centred.consistent.ols_cost, ols.consistent.ols_cost, 1e-9 * ols.consistent.ols_cost);

  // Centred half way to the truth: its β moves with the centre, away from least squares'.
  const Eigen::VectorXd half = 0.5 * (ols.linear.beta + ols.beta_model);
  ASSERT_NO_THROW(CentreConsistentFit(model_, identified.factors, options_, half, &centred));
  const Eigen::MatrixXd R = CombinedFactor(identified.factors, Eigen::VectorXd::Ones(6))
                                .topLeftCorner(half.size(), half.size()).triangularView<Eigen::Upper>();
  auto distance = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (R * (a - b)).norm(); };
  EXPECT_LT(distance(centred.consistent.beta, half), 0.5 * distance(ols.consistent.beta, half));
  // ρ_c² = ‖W β_c − τ‖²: above least squares' minimum, the cost judged against it.
  EXPECT_GT(centred.consistent.ols_cost, ols.consistent.ols_cost);
  EXPECT_GE(centred.consistent.cost, centred.consistent.ols_cost * (1 - 1e-9));
  EXPECT_TRUE(centred.verdict.fit_to_load()) << ToKey(centred.verdict.status);
  EXPECT_THROW(CentreConsistentFit(model_, identified.factors, options_, Eigen::VectorXd::Zero(3), &centred),
               std::invalid_argument);
}

// A closed-loop estimator follows one reference: several logs, or no
// controller and reference, are refused before any work.
TEST_F(LogIdentificationTest, ClosedLoopEstimatorsNeedOneLogAndTheirInputs) {
  const PreparedLog a = Log(0.0, 2.0, 1, "a.csv"), b = Log(3.0, 2.0, 2, "b.csv");
  JointTorqueOptions iv = options_;
  iv.estimator = TorqueEstimator::kInstrumentalVariables;
  int announced = 0;
  const LogStageObserver count = [&](const std::string&) -> const StreamObserver* {
    ++announced;
    return nullptr;
  };
  try {
    IdentifyFromLogs(model_, {&a, &b}, iv, nullptr, count);
    FAIL() << "two logs were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "estimator iv: one data log (it re-simulates the closed loop along one reference), got 2");
  }
  EXPECT_THROW(IdentifyFromLogs(model_, {&a}, iv, nullptr, count), std::invalid_argument);
  EXPECT_EQ(announced, 0);
}

}  // namespace
}  // namespace idbench
