// Excitation design speed: one criterion evaluation (and with its gradient)
// for puma560's base regressor, 250 samples × 6 joints × 48 parameters, and
// the whole design of issue 3's acceptance case.
#include <benchmark/benchmark.h>

#include <random>

#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {

// puma560, Fv + Fc, H = 5, f0 = 0.1 Hz, 250 samples, the limits.
struct PumaDesignCase {
  RobotModel model = MakePuma560();
  DesignRegressor regressor = DesignRegressor::JointTorque(model, Friction());
  std::vector<JointLimits> limits = Limits(model);
  DesignOptions options;

  static FrictionModel Friction() {
    FrictionModel f;
    f.viscous = f.coulomb = true;
    return f;
  }
  static std::vector<JointLimits> Limits(const RobotModel& model) {
    const double qd[6] = {1.5, 1.5, 1.5, 3, 3, 3}, qdd[6] = {4, 4, 4, 8, 8, 8};
    std::vector<JointLimits> limits;
    for (int j = 0; j < 6; ++j) {
      limits.push_back(model.link(j).limits);
      limits.back().qd_max = qd[j];
      limits.back().qdd_max = qdd[j];
    }
    return limits;
  }
};

void BenchmarkCriterion(benchmark::State& state, bool gradient) {
  const PumaDesignCase c;
  const DesignProblem problem(c.regressor, c.limits, c.options);
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(1, &ws);
  Eigen::VectorXd grad(problem.n_unknowns());
  for (auto _ : state) {
    benchmark::DoNotOptimize(problem.Criterion(theta.data(), gradient ? grad.data() : nullptr, &ws));
  }
  state.counters["parameters"] = c.regressor.n_parameters();
}
void BM_DesignCriterionPuma560(benchmark::State& state) { BenchmarkCriterion(state, false); }
BENCHMARK(BM_DesignCriterionPuma560)->Unit(benchmark::kMillisecond);
void BM_DesignCriterionGradientPuma560(benchmark::State& state) { BenchmarkCriterion(state, true); }
BENCHMARK(BM_DesignCriterionGradientPuma560)->Unit(benchmark::kMillisecond);

// The whole design with the default options (as `idbench design` runs it),
// with the constraint set (joint, velocity, acceleration limits:
// clearance off) and with the default 1 cm link and ground clearance.
void BenchmarkDesign(benchmark::State& state, double clearance) {
  PumaDesignCase c;
  c.options.clearance = clearance;
  double cond = 0.0;
  for (auto _ : state) cond = DesignExcitation(c.regressor, c.limits, c.options).final.cond;
  state.counters["cond"] = cond;
}
void BM_DesignPuma560(benchmark::State& state) { BenchmarkDesign(state, -1.0); }
BENCHMARK(BM_DesignPuma560)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
void BM_DesignPuma560WithClearance(benchmark::State& state) { BenchmarkDesign(state, 0.01); }
BENCHMARK(BM_DesignPuma560WithClearance)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// tests/data/ur10e_like (mesh links, 15 clearance pairs at 1 cm) with its
// acceleration limits, default options: one evaluation of the nonlinear
// constraints (the clearance rows: GJK over pairs × instants) with and
// without their gradient, beside one criterion evaluation with its gradient.
struct UrLikeCase {
  RobotModel model = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/ur10e_like/ur10e_like.urdf").model;
  DesignRegressor regressor = DesignRegressor::JointTorque(model, FrictionModel{});
  std::vector<JointLimits> limits;
  DesignOptions options;
  UrLikeCase() {
    const double qdd[6] = {3, 3, 5, 5, 5, 5};
    for (int j = 0; j < 6; ++j) limits.push_back(model.link(j).limits), limits.back().qdd_max = qdd[j];
  }
};

void BenchmarkUrLikeConstraints(benchmark::State& state, bool gradient) {
  const UrLikeCase c;
  DesignProblem problem(c.regressor, c.limits, c.options);
  problem.set_home((Eigen::VectorXd(6) << 0, -0.5, 0, 0, 0, 0).finished());
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(1, &ws);
  const size_t m = static_cast<size_t>(problem.n_nonlinear_constraints());
  std::vector<double> values(m), grad(m * static_cast<size_t>(problem.n_unknowns()));
  for (auto _ : state) {
    problem.NonlinearConstraints(theta.data(), values.data(), gradient ? grad.data() : nullptr, &ws);
    benchmark::DoNotOptimize(values.data());
  }
  state.counters["rows"] = static_cast<double>(m);  // torque limits and clearance pairs
}
void BM_ClearanceConstraintsUr10eLike(benchmark::State& state) { BenchmarkUrLikeConstraints(state, false); }
BENCHMARK(BM_ClearanceConstraintsUr10eLike)->Unit(benchmark::kMillisecond);
void BM_ClearanceConstraintsGradientUr10eLike(benchmark::State& state) { BenchmarkUrLikeConstraints(state, true); }
BENCHMARK(BM_ClearanceConstraintsGradientUr10eLike)->Unit(benchmark::kMillisecond);
// One criterion evaluation with its gradient at a case's first start point.
template <typename Case>
void BenchmarkCriterionGradient(benchmark::State& state) {
  const Case c;
  const DesignProblem problem(c.regressor, c.limits, c.options);
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd theta = problem.StartPoint(1, &ws);
  Eigen::VectorXd grad(problem.n_unknowns());
  for (auto _ : state) benchmark::DoNotOptimize(problem.Criterion(theta.data(), grad.data(), &ws));
}
void BM_DesignCriterionGradientUr10eLike(benchmark::State& state) { BenchmarkCriterionGradient<UrLikeCase>(state); }
BENCHMARK(BM_DesignCriterionGradientUr10eLike)->Unit(benchmark::kMillisecond);

// tests/data/panda_like (8 mesh links, 21 clearance pairs at 1 cm) with
// Franka's acceleration limits: the nonlinear constraints with their
// gradient along a walk of small steps (0.003 per unknown, as an optimizer
// takes them; one workspace), so that what one evaluation carries to the
// next counts as it does in a design. The criterion beside it for scale.
struct PandaLikeCase {
  RobotModel model = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/panda_like/panda_like.urdf").model;
  DesignRegressor regressor = DesignRegressor::JointTorque(model, FrictionModel{});
  std::vector<JointLimits> limits;
  DesignOptions options;
  PandaLikeCase() {
    const double qdd[7] = {15, 7.5, 10, 12.5, 15, 20, 20};
    for (int j = 0; j < 7; ++j) limits.push_back(model.link(j).limits), limits.back().qdd_max = qdd[j];
  }
};

void BM_ClearanceConstraintsGradientPandaLikeWalk(benchmark::State& state) {
  const PandaLikeCase c;
  const DesignProblem problem(c.regressor, c.limits, c.options);
  DesignProblem::Workspace ws(problem);
  const Eigen::VectorXd start = problem.StartPoint(1, &ws);
  std::vector<Eigen::VectorXd> walk(64, start);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 0.003);
  for (size_t k = 1; k < walk.size(); ++k) {
    walk[k] = walk[k - 1];
    for (Eigen::Index u = 0; u < walk[k].size(); ++u) walk[k][u] += normal(rng);
  }
  const size_t m = static_cast<size_t>(problem.n_nonlinear_constraints());
  std::vector<double> values(m), grad(m * static_cast<size_t>(problem.n_unknowns()));
  size_t k = 0;
  for (auto _ : state) {
    problem.NonlinearConstraints(walk[k].data(), values.data(), grad.data(), &ws);
    benchmark::DoNotOptimize(values.data());
    k = (k + 1) % walk.size();
  }
  state.counters["rows"] = static_cast<double>(m);  // torque limits and clearance pairs
}
BENCHMARK(BM_ClearanceConstraintsGradientPandaLikeWalk)->Unit(benchmark::kMillisecond);
void BM_DesignCriterionGradientPandaLike(benchmark::State& state) { BenchmarkCriterionGradient<PandaLikeCase>(state); }
BENCHMARK(BM_DesignCriterionGradientPandaLike)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
