// Engine speed: RNEA, and the Bullet simulation with joint feedback and recording.
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/simulation.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

void BenchmarkInverseDynamics(benchmark::State& state, const RobotModel& model) {
  RobotData data(model);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Eigen::VectorXd q(6), qd(6), qdd(6);
  for (int i = 0; i < 6; ++i) q[i] = u(rng), qd[i] = u(rng), qdd[i] = u(rng);
  for (auto _ : state) {
    benchmark::DoNotOptimize(InverseDynamics(model, q, qd, qdd, &data).data());
  }
}
void BM_InverseDynamicsPaper6r(benchmark::State& state) { BenchmarkInverseDynamics(state, MakePaper6r()); }
BENCHMARK(BM_InverseDynamicsPaper6r);
void BM_InverseDynamicsPuma560(benchmark::State& state) { BenchmarkInverseDynamics(state, MakePuma560()); }
BENCHMARK(BM_InverseDynamicsPuma560);

// One simulated step = computed torque (RNEA) + Bullet step with corrected
// feedback + recording (kinematics, quaternion rates, feedback copy).
void BM_SimulatePaper6rPerStep(benchmark::State& state) {
  const RobotModel model = MakePaper6r();
  const auto motion = MakeGeneralMotion(6, 2.0);
  SimulationOptions options;
  options.duration = 2.0;
  const int64_t steps = std::lround(options.duration / options.dt);
  for (auto _ : state) {
    const SimulationLog log = Simulate(model, *motion, options);
    benchmark::DoNotOptimize(log.steps.back().q.data());
  }
  state.SetItemsProcessed(state.iterations() * steps);
}
BENCHMARK(BM_SimulatePaper6rPerStep)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
