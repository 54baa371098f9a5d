// Identification speed: the joint-torque regressor per sample, and stacking
// plus OLS over a long log.
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <cmath>
#include <random>

#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/ident/plausible_fit.h"
#include "idbench/ident/streamed_joint_equations.h"
#include "idbench/logs/streamed_log_filter.h"

namespace idbench {
namespace {

void BenchmarkRegressor(benchmark::State& state, const RobotModel& model) {
  RobotData data(model);
  FrictionModel friction;
  friction.viscous = friction.coulomb = true;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Eigen::VectorXd q(6), qd(6), qdd(6);
  for (int i = 0; i < 6; ++i) q[i] = u(rng), qd[i] = u(rng), qdd[i] = u(rng);
  Eigen::MatrixXd Y(6, NumStandardParameters(model, friction));
  for (auto _ : state) {
    ComputeJointTorqueRegressor(model, friction, q, qd, qdd, &data, &Y);
    benchmark::DoNotOptimize(Y.data());
  }
}

void BM_JointTorqueRegressorPaper6r(benchmark::State& state) { BenchmarkRegressor(state, MakePaper6r()); }
BENCHMARK(BM_JointTorqueRegressorPaper6r);
void BM_JointTorqueRegressorPuma560(benchmark::State& state) { BenchmarkRegressor(state, MakePuma560()); }
BENCHMARK(BM_JointTorqueRegressorPuma560);

// puma560 with Fv, Fc (48 base parameters) and a random log of n_samples
// states in ±2 (rad, rad/s, rad/s²) and torques.
struct Puma560Problem {
  RobotModel model = MakePuma560();
  FrictionModel friction{.viscous = true, .coulomb = true};
  BaseParameters base = ComputeBaseParameters(model, friction);
  JointLog log;

  explicit Puma560Problem(int n_samples) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    log.t = Eigen::VectorXd::LinSpaced(n_samples, 0.0, 1e-3 * (n_samples - 1));
    log.q = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return u(rng); });
    log.qd = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return u(rng); });
    log.qdd = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return u(rng); });
    log.tau = Eigen::MatrixXd::NullaryExpr(n_samples, 6, [&] { return u(rng); });
  }
};

// Stack the base regressor over N samples and solve OLS with σ and cond: the
// whole identification after the log is read. Streamed: per-joint TSQR
// factors, never the 6N × 48 W, on the given number of threads (range 1).
void BM_StackAndOlsPuma560(benchmark::State& state) {
  const Puma560Problem p(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const StackedFactors factors =
        FactorStackedEquations(p.model, p.friction, p.base, p.log, static_cast<int>(state.range(1)));
    const LinearFit fit = SolveOls(factors);
    benchmark::DoNotOptimize(fit.beta.data());
  }
}
BENCHMARK(BM_StackAndOlsPuma560)
    ->Args({10000, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The stacked base regressor W alone (6N × 48): what Python's
// idbench.regressor returns (python_regressor_benchmark.py, the same problem).
void BM_StackBaseRegressorPuma560(benchmark::State& state) {
  const Puma560Problem p(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const Eigen::MatrixXd W = StackBaseRegressor(p.model, p.friction, p.base, p.log);
    benchmark::DoNotOptimize(W.data());
  }
}
BENCHMARK(BM_StackBaseRegressorPuma560)->Arg(100000)->Unit(benchmark::kMillisecond);

// The same through the whole stacked W (StackBaseRegressor, then SolveOls on
// W), as IdentifyJointTorque does (its physically consistent fit needs W).
void BM_StackDenseAndOlsPuma560(benchmark::State& state) {
  const Puma560Problem p(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const Eigen::MatrixXd W = StackBaseRegressor(p.model, p.friction, p.base, p.log);
    const LinearFit fit = SolveOls(W, StackTorques(p.log), 6);
    benchmark::DoNotOptimize(fit.beta.data());
  }
}
BENCHMARK(BM_StackDenseAndOlsPuma560)->Arg(100000)->Unit(benchmark::kMillisecond);

// The physically consistent estimate from the triangular factor of [W τ]
// (its cost does not depend on the number of samples): torques of the PUMA
// 560 itself (Fv, Fc from the robot file) along random states, with noise, so
// that some bounds are active: the plausible fit (barrier method on the SDP,
// bounds and prior) that `identify` runs.
struct Puma560ConsistentProblem {
  Puma560Problem p{2000};
  Eigen::MatrixXd factor;
  Eigen::VectorXd pi_model;
  Puma560ConsistentProblem() {
    pi_model = StandardParameters(p.model, p.friction);
    const Eigen::MatrixXd W = StackBaseRegressor(p.model, p.friction, p.base, p.log);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.5);
    Eigen::VectorXd tau = W * (p.base.combination * pi_model);
    for (Eigen::Index r = 0; r < tau.size(); ++r) tau[r] += noise(rng);
    factor = CombinedFactor(W, tau);
  }
};

void BM_PlausibleFitPuma560(benchmark::State& state) {
  const Puma560ConsistentProblem c;
  const PlausibleFitOptions options = MakePlausibleFitOptions(c.p.model, c.p.friction, PlausibilitySettings{});
  for (auto _ : state) {
    const PhysicallyConsistentFit fit = SolvePlausibleFit(c.factor, c.p.base, 6, c.pi_model, options);
    benchmark::DoNotOptimize(fit.pi.data());
    state.counters["gap"] = fit.duality_gap;
    state.counters["newton_steps"] = fit.evaluations;
  }
}
BENCHMARK(BM_PlausibleFitPuma560)->Unit(benchmark::kMillisecond);

// The streamed core of `identify` on a controller's log (t, q, measured qd,
// τ at 1 kHz; no qdd), generated chunk by chunk so that nothing but the
// pipeline holds memory: StreamedLogFilter (zero-phase filter, qdd from qd),
// StreamedJointEquations (regressor, parallel filter, fold), then OLS. puma560
// with Fv, Fc (48 base parameters), default filter (order 4, 10 Hz, 5/fc
// trimmed). The counter peak_rss_mb is the process's peak so far.
void BM_StreamedIdentifyPuma560(benchmark::State& state) {
  const Eigen::Index n = state.range(0);
  const RobotModel model = MakePuma560();
  FrictionModel friction;
  friction.viscous = friction.coulomb = true;
  const BaseParameters base = ComputeBaseParameters(model, friction);
  const ParallelFilter filter{.filter = {.trim_s = -1.0}, .sample_rate_hz = 1000.0};
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (auto _ : state) {
    StreamedLogFilter prepare(filter.filter, filter.sample_rate_hz, true, false, 6, n);
    StreamedEquationsSettings settings;
    settings.filter = filter;
    settings.n_samples = n;
    StreamedJointEquations equations(model, friction, base, settings);
    JointLog chunk;
    for (Eigen::Index s0 = 0; s0 < n; s0 += kStreamBlockSamples) {
      const Eigen::Index m = std::min(kStreamBlockSamples, n - s0);
      chunk.t.resize(m);
      chunk.q.resize(m, 6);
      chunk.qd.resize(m, 6);
      chunk.tau.resize(m, 6);
      for (Eigen::Index s = 0; s < m; ++s) {
        const double t = 1e-3 * static_cast<double>(s0 + s);
        chunk.t[s] = t;
        for (int j = 0; j < 6; ++j) {
          const double w = 0.3 + 0.2 * j;
          chunk.q(s, j) = std::sin(w * t + j);
          chunk.qd(s, j) = w * std::cos(w * t + j) + 1e-3 * noise(rng);
          chunk.tau(s, j) = 10.0 * std::sin(w * t) + noise(rng);
        }
      }
      prepare.Push(chunk, [&](const JointLog& prepared, Eigen::Index) { equations.Push(prepared); });
    }
    benchmark::DoNotOptimize(SolveOls(equations.factors()).beta.data());
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
BENCHMARK(BM_StreamedIdentifyPuma560)->Arg(100000)->Arg(1200000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
