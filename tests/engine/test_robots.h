// Robots for tests beyond paper6r.
#pragma once

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <random>
#include <string>

#include "engine/test_util.h"
#include "idbench/engine/paper6r.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/robot_model.h"

namespace idbench::testing {

// A robot whose link frames are not principal frames: tilted axes, offset
// centres of mass and full inertia tensors, so the principal-frame mapping
// to Bullet is exercised.
inline RobotModel MakeTiltedRobot() {
  std::mt19937 rng(5);
  std::vector<Link> links(4);
  for (int i = 0; i < 4; ++i) {
    Link& link = links[static_cast<size_t>(i)];
    link.name = "L" + std::to_string(i);
    link.parent = i - 1;
    link.axis_J = RandomVector(3, 1.0, &rng).normalized();
    link.X_PJ.linear() = Eigen::AngleAxisd(0.4 * (i + 1), RandomVector(3, 1.0, &rng).normalized()).toRotationMatrix();
    link.X_PJ.translation() = i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5, 0.1, -0.2);
    link.inertia.mass = 3.0 + i;
    link.inertia.p_BoBcm_B = RandomVector(3, 0.3, &rng);
    const Eigen::Matrix3d A = Eigen::Map<const Eigen::Matrix3d>(RandomVector(9, 1.0, &rng).data());
    link.inertia.I_Bcm_B = A * A.transpose() + 0.2 * Eigen::Matrix3d::Identity();
  }
  return RobotModel("tilted4r", std::move(links));
}

// The robots every identity is checked on, for parameterised tests.
inline constexpr int kNumTestRobots = 3;
inline RobotModel MakeTestRobot(int index) {
  switch (index) {
    case 0: return MakePaper6r();
    case 1: return MakeTiltedRobot();
    default: return MakePuma560();
  }
}
inline std::string TestRobotName(const ::testing::TestParamInfo<int>& info) {
  return MakeTestRobot(info.param).name();
}

}  // namespace idbench::testing
