// Shared helpers for the tests.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

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

// The message of the std::invalid_argument that f throws; a test failure
// (and "") if it throws none.
inline std::string ExpectInvalid(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::invalid_argument";
  return "";
}

}  // namespace idbench::testing
