#include "idbench/ident/joint_torque_identifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <utility>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/ident/signal_filter.h"
#include "ident/synthetic_log.h"

namespace idbench {
namespace {

// Noise-free puma560 logs along the general motion (rigid body + Fv, Fc, Ia
// of the robot file: the file's base parameters are the truth).
class PredictTorqueSeriesTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePuma560();
  std::unique_ptr<Trajectory> motion_ = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  JointTorqueOptions options_ = [] {
    JointTorqueOptions o;
    o.friction = {.viscous = true, .coulomb = true, .rotor_inertia = true};
    return o;
  }();
  BaseParameters base_ = ComputeBaseParameters(model_, options_.friction);
  Eigen::VectorXd beta_file_ = base_.combination * StandardParameters(model_, options_.friction);

  JointLog Log(int n_samples) const {
    return testing::SyntheticJointLog(model_, *motion_, Eigen::VectorXd::LinSpaced(n_samples, 0.0, 10.0));
  }
  // β_file with every entry off by 2–8 %, so that τ̂ − τ is well above rounding.
  Eigen::VectorXd WrongBeta() const {
    Eigen::VectorXd beta = beta_file_;
    for (Eigen::Index k = 0; k < beta.size(); ++k) beta[k] *= 1.0 + 0.05 + 0.03 * std::sin(1.7 * static_cast<double>(k));
    return beta;
  }
  // RMS over the rows, per column.
  static Eigen::VectorXd ColumnRms(const Eigen::MatrixXd& x) {
    return (x.colwise().squaredNorm() / static_cast<double>(x.rows())).cwiseSqrt().transpose();
  }
};

// Without a filter every sample is kept as read, and W β of the true (or the
// identified) base parameters is the logged torque to rounding, per joint.
TEST_F(PredictTorqueSeriesTest, NoiseFreeLogIsPredictedToRounding) {
  const JointLog log = Log(1001);
  const JointTorqueIdentification id = IdentifyJointTorque(model_, log, options_);
  for (const Eigen::VectorXd* beta : {&std::as_const(beta_file_), &id.beta}) {
    const TorqueSeries series = PredictTorqueSeries(model_, options_, id.base, *beta, log);
    ASSERT_EQ(series.t.size(), 1001);
    EXPECT_EQ(series.t, log.t);
    EXPECT_EQ(series.measured, log.tau);
    const Eigen::VectorXd joint_error = (series.predicted - series.measured).colwise().norm().transpose();
    const Eigen::VectorXd joint_norm = series.measured.colwise().norm().transpose();
    std::printf("largest per-joint relative error: %.3g\n", joint_error.cwiseQuotient(joint_norm).maxCoeff());
    EXPECT_LT(joint_error.cwiseQuotient(joint_norm).maxCoeff(), 1e-9);
  }
}

// τ̂ and τ are the rows PredictTorques scores, in the same order: with wrong
// parameters the RMS per joint of the series equals PredictTorques'
// joint_rms (computed through the TSQR factors, without W, when there is no
// filter), and the relative error too; with a parallel filter the time stamps
// are those of the kept samples.
TEST_F(PredictTorqueSeriesTest, RowsAreThoseOfTheTorqueRms) {
  const JointLog log = Log(2001);  // 200 Hz
  const ParallelFilter filter{.filter = {.order = 4, .cutoff_hz = 10.0, .decimation = 3, .trim_s = -1.0},
                              .sample_rate_hz = 200.0};
  const Eigen::VectorXd beta = WrongBeta();
  for (const std::optional<ParallelFilter>& parallel : {std::optional<ParallelFilter>(), std::optional(filter)}) {
    JointTorqueOptions options = options_;
    options.parallel_filter = parallel;
    const TorqueSeries series = PredictTorqueSeries(model_, options, base_, beta, log);
    const TorquePrediction scored = PredictTorques(model_, options, base_, beta, log);
    const Eigen::MatrixXd residual = series.predicted - series.measured;
    const Eigen::VectorXd rms = ColumnRms(residual);
    std::printf("%s: joint RMS %.3g to %.3g N m, |rms - joint_rms|/joint_rms <= %.3g\n",
                parallel ? "filtered" : "as read", rms.minCoeff(), rms.maxCoeff(),
                (rms - scored.joint_rms).cwiseAbs().cwiseQuotient(scored.joint_rms).maxCoeff());
    EXPECT_GT(rms.minCoeff(), 1e-3);  // a real residual, not rounding
    EXPECT_LT((rms - scored.joint_rms).cwiseAbs().cwiseQuotient(scored.joint_rms).maxCoeff(), 1e-12);
    EXPECT_NEAR(residual.norm() / series.measured.norm(), scored.relative_error, 1e-12 * scored.relative_error);
    if (!parallel) {
      EXPECT_EQ(series.t, log.t);
      continue;
    }
    // 0.5 s = 100 samples trimmed at both ends, every 3rd kept: 100, 103, …, 1900.
    ASSERT_EQ(series.t.size(), 601);
    for (Eigen::Index k = 0; k < series.t.size(); ++k) ASSERT_EQ(series.t[k], log.t[100 + 3 * k]) << k;
    // The filter is linear: filtered W β_file is the filtered torque.
    const TorqueSeries exact = PredictTorqueSeries(model_, options, base_, beta_file_, log);
    EXPECT_EQ(exact.t, series.t);
    EXPECT_EQ(exact.measured, series.measured);
    EXPECT_LT((exact.predicted - exact.measured).norm() / exact.measured.norm(), 1e-9);
    // Row k is sample 100 + 3k of the torque filtered on its own (FiltFilt
    // per joint column, not through the stacked rows), and not its neighbour.
    const Eigen::MatrixXd tau_f = FiltFilt(DesignButterworthLowPass(4, 10.0, 200.0), log.tau);
    Eigen::MatrixXd at_t(601, 6), later(601, 6);
    for (Eigen::Index k = 0; k < 601; ++k) {
      at_t.row(k) = tau_f.row(100 + 3 * k);
      later.row(k) = tau_f.row(101 + 3 * k);
    }
    const double here = (series.measured - at_t).norm() / at_t.norm();
    const double shifted = (series.measured - later).norm() / at_t.norm();
    std::printf("filtered torque vs FiltFilt(tau): %.3g at the sample, %.3g one sample later\n", here, shifted);
    EXPECT_LT(here, 1e-12);
    EXPECT_GT(shifted, 1e-3);
  }
}

TEST_F(PredictTorqueSeriesTest, WrongNumberOfParametersThrows) {
  EXPECT_THROW(PredictTorqueSeries(model_, options_, base_, Eigen::VectorXd::Zero(base_.n_base() - 1), Log(101)),
               std::invalid_argument);
}

}  // namespace
}  // namespace idbench
