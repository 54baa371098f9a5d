// Checks shared by the trajectory tests.
#pragma once

#include <gtest/gtest.h>

#include "idbench/engine/trajectory.h"

namespace idbench::testing {

// Analytic qd, qdd against central differences of q and qd (h = 1e-5:
// truncation O(h²) ≈ 1e-10, rounding O(ε/h) ≈ 1e-11).
inline void ExpectConsistentDerivatives(const Trajectory& traj, double first = 0.1, double step = 0.37) {
  const double h = 1e-5;
  for (double t = first; t < traj.duration() - first; t += step) {
    const JointState s = traj.At(t), sp = traj.At(t + h), sm = traj.At(t - h);
    EXPECT_LT(((sp.q - sm.q) / (2 * h) - s.qd).cwiseAbs().maxCoeff(), 1e-8) << "t = " << t;
    EXPECT_LT(((sp.qd - sm.qd) / (2 * h) - s.qdd).cwiseAbs().maxCoeff(), 1e-8) << "t = " << t;
  }
}

}  // namespace idbench::testing
