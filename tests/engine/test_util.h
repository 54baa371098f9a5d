// Shared helpers for engine tests.
#pragma once

#include <Eigen/Core>
#include <random>

namespace idbench::testing {

// Uniform random vector in [-scale, scale]^n, deterministic per seed.
inline Eigen::VectorXd RandomVector(int n, double scale, std::mt19937* rng) {
  std::uniform_real_distribution<double> dist(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = dist(*rng);
  return v;
}

// max |a − b| / max |b|, the relative error used throughout the tests.
template <typename A, typename B>
double RelativeError(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace idbench::testing
