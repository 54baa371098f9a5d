// Identification speed: the joint-torque regressor per sample.
#include <benchmark/benchmark.h>

#include <random>

#include "idbench/engine/paper6r.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {
namespace {

void BM_JointTorqueRegressorPaper6r(benchmark::State& state) {
  const RobotModel model = MakePaper6r();
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
BENCHMARK(BM_JointTorqueRegressorPaper6r);

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
