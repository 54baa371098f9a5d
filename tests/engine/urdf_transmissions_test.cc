// ros_control <transmission> elements read with a URDF (urdf_transmissions.cc).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

// Three revolute joints j1..j3 in a row and a finger on a prismatic joint,
// followed by `transmissions`.
std::string ArmUrdf(const std::string& transmissions) {
  std::string links = R"(<link name="base"/>)";
  std::string joints;
  const char* parent = "base";
  const char* names[] = {"l1", "l2", "l3"};
  for (int i = 0; i < 3; ++i) {
    links += std::string(R"(<link name=")") + names[i] +
             R"("><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>)";
    joints += "<joint name=\"j" + std::to_string(i + 1) + "\" type=\"revolute\"><parent link=\"" + parent +
              "\"/><child link=\"" + names[i] + "\"/><origin xyz=\"0 0 0.3\"/><axis xyz=\"0 1 0\"/>"
              "<limit lower=\"-3\" upper=\"3\" effort=\"100\" velocity=\"3\"/></joint>";
    parent = names[i];
  }
  links += R"(<link name="finger"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>)";
  joints += R"(<joint name="finger_joint" type="prismatic"><parent link="l3"/><child link="finger"/><axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>)";
  return "<robot name=\"arm\">" + links + joints + transmissions + "</robot>";
}

TEST(UrdfTransmissionsTest, SimpleTransmissionsGiveTheReductions) {
  const std::string transmissions = R"(
    <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j1"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m1"><mechanicalReduction>100</mechanicalReduction></actuator></transmission>
    <transmission name="t2" type="pr2_mechanism_model/SimpleTransmission">
      <joint name="j2"/><actuator name="m2"/><mechanicalReduction>-50.5</mechanicalReduction></transmission>
    <transmission name="t_finger"><type>transmission_interface/SimpleTransmission</type>
      <joint name="finger_joint"/><actuator name="mf"><mechanicalReduction>7</mechanicalReduction></actuator></transmission>)";
  const UrdfLoadResult loaded = LoadUrdfString(ArmUrdf(transmissions), "arm.urdf");
  ASSERT_TRUE(loaded.transmission.has_value());
  Eigen::MatrixXd expected = Eigen::Vector3d(100, -50.5, 1).asDiagonal();
  EXPECT_EQ(loaded.transmission->actuator_from_joint, expected);
  EXPECT_EQ(loaded.transmission->source, "arm.urdf (<transmission>)");
  bool warned = false;
  for (const std::string& w : loaded.warnings) {
    warned = warned || w == "arm.urdf: no SimpleTransmission for joint(s) 'j3': taken as direct drive (reduction 1)";
  }
  EXPECT_TRUE(warned);
}

TEST(UrdfTransmissionsTest, NoneOrBadOnes) {
  EXPECT_FALSE(LoadUrdfString(ArmUrdf(""), "arm.urdf").transmission.has_value());
  const std::string bad = R"(<transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j1"/><actuator name="m1"><mechanicalReduction>fast</mechanicalReduction></actuator></transmission>)";
  try {
    LoadUrdfString(ArmUrdf(bad), "arm.urdf");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "arm.urdf:1: transmission 't1': mechanicalReduction: expected one finite non-zero number, got 'fast'");
  }
  const std::string differential = R"(<transmission name="t3"><type>transmission_interface/DifferentialTransmission</type>
      <joint name="j3"/></transmission>)";
  const UrdfLoadResult loaded = LoadUrdfString(ArmUrdf(differential), "arm.urdf");
  EXPECT_FALSE(loaded.transmission.has_value());
  ASSERT_FALSE(loaded.warnings.empty());
  EXPECT_NE(loaded.warnings.back().find("type 'transmission_interface/DifferentialTransmission' not read"),
            std::string::npos) << loaded.warnings.back();
}

// Issue 35 item 26: a transmission naming a joint the robot lacks (j2 typed
// "j_2") was dropped, and j2 became direct drive (reduction 1 instead of 160).
TEST(UrdfTransmissionsTest, RefusesAJointTheRobotLacks) {
  const auto error = [](const std::string& transmissions) {
    try {
      LoadUrdfString(ArmUrdf(transmissions), "arm.urdf");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string t1 = R"(<transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j1"/><actuator name="m1"><mechanicalReduction>100</mechanicalReduction></actuator></transmission>)";
  EXPECT_EQ(error(t1 + R"(
    <transmission name="t2"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j_2"/><actuator name="m2"><mechanicalReduction>160</mechanicalReduction></actuator></transmission>)"),
            "arm.urdf:3: transmission 't2': <joint name=\"j_2\">: the robot has no joint 'j_2' (joints: 'j1', 'j2', "
            "'j3', 'finger_joint')");
  EXPECT_EQ(error(t1 + R"(
    <transmission name="t2"><type>transmission_interface/SimpleTransmission</type>
      <actuator name="m2"><mechanicalReduction>160</mechanicalReduction></actuator></transmission>)"),
            "arm.urdf:3: transmission 't2': no <joint name=\"...\"> in it; a transmission names the joint it drives");
  // A joint off the chain (the finger) is still taken and left out.
  EXPECT_EQ(error(t1 + R"(<transmission name="tf"><type>transmission_interface/SimpleTransmission</type>
      <joint name="finger_joint"/><actuator name="mf"><mechanicalReduction>7</mechanicalReduction></actuator></transmission>)"),
            "(no error)");
}

}  // namespace
}  // namespace idbench
