// Shared settings of the excitation-design tests.
#pragma once

#include <cmath>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench::testing {

// The robot's limits with the given velocity and acceleration limits on every
// joint, and ±3 rad where the robot has no position limits.
inline std::vector<JointLimits> DesignLimits(const RobotModel& model, double qd_max, double qdd_max) {
  std::vector<JointLimits> limits;
  for (const Link& link : model.links()) {
    limits.push_back(link.limits);
    limits.back().qd_max = qd_max;
    limits.back().qdd_max = qdd_max;
    if (!std::isfinite(limits.back().q_min)) limits.back().q_min = -3.0, limits.back().q_max = 3.0;
  }
  return limits;
}

inline FrictionModel ViscousCoulomb() {
  FrictionModel f;
  f.viscous = f.coulomb = true;
  return f;
}

}  // namespace idbench::testing
