// Robots for tests beyond paper6r.
#pragma once

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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

// ---- Vendor-style URDF text ----

// A Panda-like arm as example-robot-data ships it: panda_link0 (root),
// panda_joint1..7 revolute (the Panda's joint origins; links 1–6 of 1 kg with
// diag(0.1, 0.1, 0.1) kg m²), link 7 (0.4 kg, COM (0, 0, 0.05), diag(3, 3, 2)e-3),
// panda_link8 without <inertial> on a fixed joint 0.107 m up z, panda_hand
// fixed to it turned by Rz(−π/4) (0.73 kg, COM (−0.01, 0, 0.03), diag(1, 2.5,
// 1.7)e-3, a box visual), and two prismatic fingers 0.0584 m up the hand's z,
// sliding along +y and −y of the hand (limits [0, 0.04] m), finger 2 a
// <mimic> of finger 1; each finger 0.015 kg, COM (0, ±0.01, 0.02) in its
// frame, diag(2.375, 2.375, 0.75)e-6, a box visual.
// With `fingers_fixed`, the finger joints are fixed ones with their origins
// shifted by ±finger_q along the hand's y: the same bodies, held by hand.
inline std::string PandaLikeUrdf(bool fingers_fixed = false, double finger_q = 0.0) {
  const auto link = [](const std::string& name, const std::string& mass, const std::string& com,
                       const std::string& inertia, const std::string& box) {
    std::string text = "<link name=\"" + name + "\">";
    if (!mass.empty()) {
      std::istringstream in(inertia);
      std::string d[3];
      in >> d[0] >> d[1] >> d[2];
      text += "<inertial><origin xyz=\"" + com + "\"/><mass value=\"" + mass + "\"/><inertia ixx=\"" + d[0] +
              "\" ixy=\"0\" ixz=\"0\" iyy=\"" + d[1] + "\" iyz=\"0\" izz=\"" + d[2] + "\"/></inertial>";
    }
    if (!box.empty()) text += "<visual><geometry><box size=\"" + box + "\"/></geometry></visual>";
    return text + "</link>\n";
  };
  const auto joint = [](const std::string& name, const std::string& type, const std::string& parent,
                        const std::string& child, const std::string& xyz, const std::string& rpy,
                        const std::string& extra) {
    return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" +
           child + "\"/><origin xyz=\"" + xyz + "\" rpy=\"" + rpy + "\"/>" + extra + "</joint>\n";
  };
  const std::string arm_limit = "<axis xyz=\"0 0 1\"/><limit lower=\"-2.8\" upper=\"2.8\" effort=\"87\" velocity=\"2.1\"/>";
  const char* xyz[7] = {"0 0 0.333", "0 0 0", "0 -0.316 0", "0.0825 0 0", "-0.0825 0.384 0", "0 0 0", "0.088 0 0"};
  const char* rpy[7] = {"0 0 0", "-1.5707963267948966 0 0", "1.5707963267948966 0 0", "1.5707963267948966 0 0",
                        "-1.5707963267948966 0 0", "1.5707963267948966 0 0", "1.5707963267948966 0 0"};
  std::string xml = "<?xml version=\"1.0\"?>\n<robot name=\"panda\">\n";
  xml += link("panda_link0", "2.9", "0 0 0.05", "0.01 0.01 0.01", "0.2 0.2 0.1");
  for (int i = 1; i <= 7; ++i) {
    const std::string n = std::to_string(i);
    xml += i < 7 ? link("panda_link" + n, "1", "0 0 0", "0.1 0.1 0.1", "")
                 : link("panda_link7", "0.4", "0 0 0.05", "0.003 0.003 0.002", "");
    xml += joint("panda_joint" + n, "revolute", "panda_link" + std::to_string(i - 1), "panda_link" + n,
                 xyz[i - 1], rpy[i - 1], arm_limit);
  }
  xml += link("panda_link8", "", "", "", "");
  xml += joint("panda_joint8", "fixed", "panda_link7", "panda_link8", "0 0 0.107", "0 0 0", "");
  xml += link("panda_hand", "0.73", "-0.01 0 0.03", "0.001 0.0025 0.0017", "0.05 0.2 0.06");
  xml += joint("panda_hand_joint", "fixed", "panda_link8", "panda_hand", "0 0 0", "0 0 -0.7853981633974483", "");
  xml += link("panda_leftfinger", "0.015", "0 0.01 0.02", "2.375e-6 2.375e-6 7.5e-7", "0.02 0.02 0.05");
  xml += link("panda_rightfinger", "0.015", "0 -0.01 0.02", "2.375e-6 2.375e-6 7.5e-7", "0.02 0.02 0.05");
  const std::string finger_limit = "<limit lower=\"0\" upper=\"0.04\" effort=\"20\" velocity=\"0.2\"/>";
  if (fingers_fixed) {
    const std::string q = std::to_string(finger_q);
    xml += joint("panda_finger_joint1", "fixed", "panda_hand", "panda_leftfinger", "0 " + q + " 0.0584", "0 0 0", "");
    xml += joint("panda_finger_joint2", "fixed", "panda_hand", "panda_rightfinger", "0 -" + q + " 0.0584", "0 0 0", "");
  } else {
    xml += joint("panda_finger_joint1", "prismatic", "panda_hand", "panda_leftfinger", "0 0 0.0584", "0 0 0",
                 "<axis xyz=\"0 1 0\"/>" + finger_limit);
    xml += joint("panda_finger_joint2", "prismatic", "panda_hand", "panda_rightfinger", "0 0 0.0584", "0 0 0",
                 "<axis xyz=\"0 -1 0\"/>" + finger_limit + "<mimic joint=\"panda_finger_joint1\"/>");
  }
  return xml + "</robot>\n";
}

}  // namespace idbench::testing
