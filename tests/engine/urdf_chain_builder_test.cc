#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "engine/urdf_test_util.h"
#include "idbench/engine/bullet_simulation.h"
#include "idbench/engine/inverse_dynamics.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Fixed joints, inertial frames ----

// Two moving links; the first carries a block on a rotated fixed joint
// between the two hinges, the second a tool (with mass) and a massless frame.
// The ground carries a 100 kg base on a rotated fixed joint, which must not
// count. Truths worked by hand, see the comments.
TEST(UrdfTest, FixedLinksAreLumpedWithParallelAxes) {
  const std::string xml = R"(<?xml version="1.0"?>
<robot name="lumped">
  <link name="world"/>
  <joint name="world_to_base" type="fixed">
    <parent link="world"/><child link="base_link"/>
    <origin xyz="0 0 0.5" rpy="0 0 3.141592653589793"/>
  </joint>
  <link name="base_link">
    <inertial><mass value="100"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="1 1 1"/></geometry></visual>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base_link"/><child link="upper"/>
    <origin xyz="0.1 0 0.2" rpy="0 0 1.5707963267948966"/>
    <axis xyz="0 0 2"/>
    <limit lower="-2" upper="2" effort="0" velocity="3"/>
    <dynamics damping="0.5" friction="0.2"/>
  </joint>
  <link name="upper">
    <inertial>
      <origin xyz="0.3 0 0" rpy="0 0 1.5707963267948966"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/>
    </inertial>
  </link>
  <joint name="elbow_mount" type="fixed">
    <parent link="upper"/><child link="elbow_block"/>
    <origin xyz="0.6 0 0" rpy="1.5707963267948966 0 0"/>
  </joint>
  <link name="elbow_block">
    <inertial>
      <origin xyz="0 0 0.3"/>
      <mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/>
    </inertial>
  </link>
  <joint name="j2" type="continuous">
    <parent link="elbow_block"/><child link="lower"/>
    <origin xyz="0 0.1 0"/>
    <axis xyz="0 0 1"/>
    <limit effort="50" velocity="0"/>
  </joint>
  <link name="lower">
    <inertial>
      <origin xyz="0.2 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.004" ixy="0" ixz="0" iyy="0.005" iyz="0" izz="0.006"/>
    </inertial>
    <visual><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></visual>
    <visual><geometry><mesh filename="package://arm/lower.stl"/></geometry></visual>
  </link>
  <joint name="tool_mount" type="fixed">
    <parent link="lower"/><child link="tool"/>
    <origin xyz="0.4 0 0" rpy="0 1.5707963267948966 0"/>
  </joint>
  <link name="tool">
    <inertial>
      <origin xyz="0 0 0.1"/>
      <mass value="0.5"/>
      <inertia ixx="0.0002" ixy="0" ixz="0" iyy="0.0003" iyz="0" izz="0.0004"/>
    </inertial>
    <visual><origin xyz="0 0 0.1"/><geometry><sphere radius="0.05"/></geometry></visual>
  </link>
  <joint name="tool_frame" type="fixed">
    <parent link="tool"/><child link="tool0"/>
    <origin xyz="0 0 0.2"/>
  </joint>
  <link name="tool0"/>
</robot>
)";
  const UrdfLoadResult loaded = LoadUrdfString(xml, "lumped.urdf");
  const RobotModel& model = loaded.model;
  EXPECT_EQ(model.name(), "lumped");
  ASSERT_EQ(model.n_links(), 2);
  const Link& upper = model.link(0);
  const Link& lower = model.link(1);
  EXPECT_EQ(upper.name, "upper");
  EXPECT_EQ(upper.joint_name, "j1");
  EXPECT_EQ(upper.parent, -1);
  EXPECT_EQ(lower.name, "lower");
  EXPECT_EQ(lower.joint_name, "j2");
  EXPECT_EQ(lower.parent, 0);
  const double tol = 1e-12;

  // j1: the ground's fixed offset (0, 0, 0.5), Rz(π), then (0.1, 0, 0.2),
  // Rz(π/2): p = (0, 0, 0.5) + Rz(π)·(0.1, 0, 0.2) = (−0.1, 0, 0.7), R = Rz(−π/2).
  Eigen::Matrix3d R_PJ1;
  R_PJ1 << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  ExpectNear(upper.X_PJ.linear(), R_PJ1, tol, "R_PJ of j1");
  ExpectNear(upper.X_PJ.translation(), Eigen::Vector3d(-0.1, 0, 0.7), tol, "p_PJ of j1");
  ExpectNear(upper.axis_J, Eigen::Vector3d(0, 0, 1), tol, "axis of j1 (normalised)");
  EXPECT_EQ(upper.limits.q_min, -2.0);
  EXPECT_EQ(upper.limits.q_max, 2.0);
  EXPECT_EQ(upper.limits.qd_max, 3.0);
  EXPECT_EQ(upper.limits.tau_max, kInf);  // effort 0 = not given
  EXPECT_EQ(upper.dynamics.viscous, 0.5);
  EXPECT_EQ(upper.dynamics.coulomb, 0.2);

  // upper = upper (2 kg, COM (0.3, 0, 0), diag(0.01, 0.02, 0.03) turned by
  // Rz(π/2) → diag(0.02, 0.01, 0.03)) + elbow_block (1 kg; its frame is at
  // (0.6, 0, 0) turned by Rx(π/2), so its COM (0, 0, 0.3) is at (0.6, −0.3, 0)
  // and diag(0.001, 0.002, 0.003) becomes diag(0.001, 0.003, 0.002)).
  // m = 3, c = (2·(0.3, 0, 0) + (0.6, −0.3, 0))/3 = (0.4, −0.1, 0).
  // Offsets d = (−0.1, 0.1, 0) and (0.2, −0.2, 0); m(|d|²1 − ddᵀ) =
  // 2·[0.01 0.01 0; 0.01 0.01 0; 0 0 0.02] + [0.04 0.04 0; 0.04 0.04 0; 0 0 0.08].
  Eigen::Matrix3d I_upper;
  I_upper << 0.081, 0.06, 0, 0.06, 0.073, 0, 0, 0, 0.152;
  ExpectNear(upper.inertia.mass, 3.0, tol, "upper mass");
  ExpectNear(upper.inertia.p_BoBcm_B, Eigen::Vector3d(0.4, -0.1, 0), tol, "upper COM");
  ExpectNear(upper.inertia.I_Bcm_B, I_upper, tol, "upper inertia");
  EXPECT_TRUE(upper.shapes.empty());  // the ground's box is not the upper arm's

  // j2 hangs from elbow_block: p = (0.6, 0, 0) + Rx(π/2)·(0, 0.1, 0) =
  // (0.6, 0, 0.1), R = Rx(π/2). Continuous: no q limits; velocity 0 = not given.
  Eigen::Matrix3d R_PJ2;
  R_PJ2 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  ExpectNear(lower.X_PJ.linear(), R_PJ2, tol, "R_PJ of j2");
  ExpectNear(lower.X_PJ.translation(), Eigen::Vector3d(0.6, 0, 0.1), tol, "p_PJ of j2");
  EXPECT_EQ(lower.limits.q_min, -kInf);
  EXPECT_EQ(lower.limits.q_max, kInf);
  EXPECT_EQ(lower.limits.qd_max, kInf);
  EXPECT_EQ(lower.limits.tau_max, 50.0);
  EXPECT_EQ(lower.dynamics.viscous, 0.0);

  // lower = lower (1.5 kg at (0.2, 0, 0), diag(0.004, 0.005, 0.006)) + tool
  // (0.5 kg; frame at (0.4, 0, 0) turned by Ry(π/2), so COM (0, 0, 0.1) is at
  // (0.5, 0, 0) and diag(2, 3, 4)e-4 becomes diag(4, 3, 2)e-4); tool0 has no mass.
  // m = 2, c = (0.3 + 0.25)/2 = 0.275; m d² = 1.5·0.075² + 0.5·0.225² = 0.03375.
  ExpectNear(lower.inertia.mass, 2.0, tol, "lower mass");
  ExpectNear(lower.inertia.p_BoBcm_B, Eigen::Vector3d(0.275, 0, 0), tol, "lower COM");
  ExpectNear(lower.inertia.I_Bcm_B, Eigen::Vector3d(0.0044, 0.03905, 0.03995).asDiagonal().toDenseMatrix(),
             tol, "lower inertia");

  // Shapes: lower's box, then the tool's sphere in lower's frame; the mesh is
  // skipped with a warning.
  ASSERT_EQ(lower.shapes.size(), 2u);
  EXPECT_EQ(lower.shapes[0].kind, Shape::Kind::kBox);
  ExpectNear(lower.shapes[0].size, Eigen::Vector3d(0.4, 0.05, 0.05), tol, "box size");
  ExpectNear(lower.shapes[0].X_BG.translation(), Eigen::Vector3d(0.2, 0, 0), tol, "box position");
  EXPECT_EQ(lower.shapes[1].kind, Shape::Kind::kSphere);
  ExpectNear(lower.shapes[1].size, Eigen::Vector3d(0.05, 0.05, 0.05), tol, "sphere size");
  ExpectNear(lower.shapes[1].X_BG.translation(), Eigen::Vector3d(0.5, 0, 0), tol, "sphere position");
  ExpectNear(lower.shapes[1].X_BG.linear(), Ry(kPi / 2), tol, "sphere orientation");
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("link 'lower'"), std::string::npos) << loaded.warnings[0];
  EXPECT_NE(loaded.warnings[0].find("mesh"), std::string::npos) << loaded.warnings[0];
}

// A general inertial rpy and joint rpy: I_Bcm_B = R·I·Rᵀ with
// R = Rz(y)·Ry(p)·Rx(r); the COM is the inertial origin, unrotated.
TEST(UrdfTest, InertialAndJointRpyAreHonoured) {
  const std::string xml = Robot(BareLink("base") + R"(
<link name="arm"><inertial>
  <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 0.7"/><mass value="2.5"/>
  <inertia ixx="0.5" ixy="0.1" ixz="-0.05" iyy="0.4" iyz="0.02" izz="0.3"/>
</inertial>
<visual><origin xyz="0 0 0.25" rpy="0.3 -0.2 0.7"/><geometry><cylinder radius="0.04" length="0.5"/></geometry></visual>
</link>
<joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
  <origin xyz="1 2 3" rpy="-1.2 0.4 2.5"/><axis xyz="1 1 0"/>
  <limit lower="-1" upper="1" effort="10" velocity="2"/></joint>
)");
  const Link link = LoadUrdfString(xml).model.link(0);
  const Eigen::Matrix3d R_BI = Rz(0.7) * Ry(-0.2) * Rx(0.3);
  Eigen::Matrix3d I_I;
  I_I << 0.5, 0.1, -0.05, 0.1, 0.4, 0.02, -0.05, 0.02, 0.3;
  ExpectNear(link.inertia.I_Bcm_B, (R_BI * I_I * R_BI.transpose()).eval(), 1e-14, "I_Bcm_B");
  ExpectNear(link.inertia.p_BoBcm_B, Eigen::Vector3d(0.1, 0.2, 0.3), 1e-15, "p_BoBcm_B");
  ExpectNear(link.X_PJ.linear(), (Rz(2.5) * Ry(0.4) * Rx(-1.2)).eval(), 1e-14, "R_PJ");
  ExpectNear(link.X_PJ.translation(), Eigen::Vector3d(1, 2, 3), 0.0, "p_PJ");
  ExpectNear(link.axis_J, Eigen::Vector3d(1, 1, 0) / std::sqrt(2.0), 1e-15, "axis_J");
  ASSERT_EQ(link.shapes.size(), 1u);
  EXPECT_EQ(link.shapes[0].kind, Shape::Kind::kCylinder);
  ExpectNear(link.shapes[0].size, Eigen::Vector3d(0.04, 0.04, 0.5), 0.0, "cylinder size");
  ExpectNear(link.shapes[0].X_BG.linear(), R_BI, 1e-14, "R_BG");
}

// ---- Rejections, each naming the culprit ----

TEST(UrdfTest, RejectsUnsupportedJointTypesNamingTheJoint) {
  for (const std::string type : {"prismatic", "floating", "planar"}) {
    ExpectRejected(Robot(BareLink("base") + MassLink("a") + Joint("slider", type, "base", "a")),
                   {"joint 'slider'", type + " joints are not supported"});
  }
  // A linear axis carrying the arm: whether it belongs to the arm is not
  // clear, so the message asks for --lock (or --tip).
  const std::string rail = Robot(BareLink("base") + MassLink("carriage") + MassLink("a") + MassLink("b") +
                                 Joint("rail", "prismatic", "base", "carriage", "<axis xyz=\"1 0 0\"/>" + kLimit) +
                                 Joint("j1", "revolute", "carriage", "a") + Joint("j2", "revolute", "a", "b"));
  ExpectRejected(rail, {"joint 'rail'", "prismatic", "locked_joints rail=VALUE"});
  // A --tip below it does not make it a revolute joint.
  try {
    LoadUrdfString(rail, "<string>", "", Options({}, "b"));
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'rail': prismatic joint on the chain"), std::string::npos) << e.what();
  }
  // Locked, it holds the arm 0.3 m along x: the carriage joins the ground.
  const UrdfLoadResult locked = LoadUrdfString(rail, "<string>", "", Options({{"rail", 0.3}}));
  ASSERT_EQ(locked.model.n_dof(), 2);
  ExpectNear(locked.model.link(0).X_PJ.translation(), Eigen::Vector3d(0.3, 0, 0), 1e-15, "j1 on the locked rail");
  ASSERT_EQ(locked.warnings.size(), 1u);
  EXPECT_NE(locked.warnings[0].find("'rail' (prismatic, at 0.3 m by locked_joints, into the ground)"), std::string::npos)
      << locked.warnings[0];

  // A floating base (a mobile robot's file) can only be held at its origin.
  const std::string floating = Robot(BareLink("world") + MassLink("base") + MassLink("a") +
                                     Joint("base_joint", "floating", "world", "base", "<origin xyz=\"0 0 0.4\"/>") +
                                     Joint("j1", "revolute", "base", "a"));
  ExpectRejected(floating, {"joint 'base_joint' (floating)", "locked_joints base_joint=0 "});
  const UrdfLoadResult held =
      LoadUrdfString(floating, "<string>", "", Options({{"base_joint", 0.0}}));
  ExpectNear(held.model.link(0).X_PJ.translation(), Eigen::Vector3d(0, 0, 0.4), 0.0, "j1 on the held base");
}

TEST(UrdfTest, RejectsBranchingNamingTheLink) {
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + MassLink("b") + MassLink("c") +
                       Joint("j1", "revolute", "base", "a") + Joint("j2", "revolute", "a", "b") +
                       Joint("j3", "continuous", "a", "c", "")),
                 {"link 'a'", "'j2'", "'j3'"});
  // The second chain starts with a fixed joint: still diverges at 'a'.
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + MassLink("b") + BareLink("mount") + MassLink("c") +
                       Joint("j1", "revolute", "base", "a") + Joint("j2", "revolute", "a", "b") +
                       Joint("fix", "fixed", "a", "mount", "") + Joint("j3", "revolute", "mount", "c")),
                 {"link 'a'"});
  // Two chains from the ground.
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + MassLink("b") + Joint("j1", "revolute", "base", "a") +
                       Joint("j2", "revolute", "base", "b")),
                 {"link 'base'"});
  // Fixed side branches carry no moving joint and are fine.
  const UrdfLoadResult ok =
      LoadUrdfString(Robot(BareLink("base") + MassLink("a") + MassLink("b") + BareLink("camera") +
                           BareLink("stand") + Joint("j1", "revolute", "base", "a") +
                           Joint("j2", "revolute", "a", "b") + Joint("cam", "fixed", "a", "camera", "") +
                           Joint("stand_fix", "fixed", "base", "stand", "")));
  EXPECT_EQ(ok.model.n_links(), 2);
}

TEST(UrdfTest, RejectsMissingMassOrBadInertiaNamingTheLink) {
  const std::string chain = BareLink("base") + MassLink("a") + Joint("j1", "revolute", "base", "a") +
                            Joint("j2", "revolute", "a", "b");
  ExpectRejected(Robot(chain + BareLink("b")), {"link 'b'", "<inertial>"});
  ExpectRejected(Robot(chain + MassLink("b", "0")), {"link 'b'", "mass must be > 0"});
  ExpectRejected(Robot(chain + MassLink("b", "-2")), {"link 'b'", "mass"});
  ExpectRejected(Robot(chain + MassLink("b", "1", "-1 0 0 0.1 0 0.1")), {"link 'b'", "<inertial>/<inertia>"});
  // A negative mass on a fixed attachment names the attachment.
  ExpectRejected(Robot(chain + MassLink("b") + MassLink("tool", "-1") + Joint("fix", "fixed", "b", "tool", "")),
                 {"link 'tool'", "mass"});
}

// Finite but absurd inertials (a mass of 1e200 kg hung every identify on
// main 6ab1a0b, OLS too) are refused at load, naming the link and field.
TEST(UrdfTest, RejectsInertialsBeyondAnyRobotNamingLinkAndField) {
  const std::string chain = BareLink("base") + MassLink("a") + Joint("j1", "revolute", "base", "a") +
                            Joint("j2", "revolute", "a", "b");
  ExpectRejected(Robot(chain + MassLink("b", "1e200")), {"link 'b'", "<inertial>/<mass>", "1e+200 kg", "at most 1e+06"});
  ExpectRejected(Robot(chain + MassLink("b", "1", "1e20 0 0 1e20 0 1e20")), {"link 'b'", "<inertial>/<inertia>", "1e+20"});
  ExpectRejected(Robot(chain + "<link name=\"b\"><inertial><origin xyz=\"1e5 0 0\"/><mass value=\"1\"/><inertia ixx=\"1\" "
                               "ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"),
                 {"link 'b'", "<inertial>/<origin>", "100000 m"});
  // The largest accepted: 10⁶ kg.
  EXPECT_EQ(LoadUrdfString(Robot(chain + MassLink("b", "1e6"))).model.link(1).inertia.mass, 1e6);
}

// A link whose centre of mass lies outside the box around its shapes (as in
// a file whose meshes are not placed in the frames of its inertials) loads
// with one warning naming it and the distance: a 10 cm cube at the link
// origin, the centre of mass at x = 0.5 m: 0.5 − 0.05 = 0.45 m outside
// (tolerance max(1 cm, 10 % of the 0.173 m diagonal) = 1.73 cm). At
// x = 0.06 m (1 cm outside, within the tolerance) it is near: no warning.
TEST(UrdfTest, WarnsWhenTheCentreOfMassLiesOutsideItsShapes) {
  auto robot = [](const std::string& x) {
    return Robot(BareLink("base") + "<link name=\"a\"><inertial><origin xyz=\"" + x +
                 " 0 0\"/><mass value=\"2\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" "
                 "izz=\"0.1\"/></inertial><visual><geometry><box size=\"0.1 0.1 0.1\"/></geometry></visual></link>\n" +
                 Joint("j1", "revolute", "base", "a"));
  };
  const UrdfLoadResult far = LoadUrdfString(robot("0.5"));
  ASSERT_EQ(far.warnings.size(), 1u);
  EXPECT_NE(far.warnings[0].find("link 'a'"), std::string::npos) << far.warnings[0];
  EXPECT_NE(far.warnings[0].find("0.45 m outside the box around its shapes"), std::string::npos) << far.warnings[0];
  EXPECT_NE(far.warnings[0].find("within 0.0173205 m"), std::string::npos) << far.warnings[0];
  EXPECT_TRUE(LoadUrdfString(robot("0.06")).warnings.empty());
}

TEST(UrdfTest, RejectsBadJointDataNamingTheJoint) {
  const std::string links = BareLink("base") + MassLink("a") + MassLink("b") + Joint("j1", "revolute", "base", "a");
  ExpectRejected(Robot(links + Joint("j2", "revolute", "a", "b",
                                     "<limit lower=\"1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>")),
                 {"joint 'j2'", "lower < upper"});
  ExpectRejected(Robot(links + Joint("j2", "revolute", "a", "b",
                                     "<limit lower=\"2\" upper=\"-2\" effort=\"1\" velocity=\"1\"/>")),
                 {"joint 'j2'", "lower < upper"});
  // No lower/upper at all: urdfdom's defaults 0, 0.
  ExpectRejected(Robot(links + Joint("j2", "revolute", "a", "b", "<limit effort=\"1\" velocity=\"1\"/>")),
                 {"joint 'j2'"});
  ExpectRejected(Robot(links + Joint("j2", "revolute", "a", "b", "<axis xyz=\"0 0 0\"/>" + kLimit)),
                 {"joint 'j2'", "axis"});
  ExpectRejected(Robot(links + Joint("j2", "revolute", "a", "b", "<dynamics damping=\"-1\"/>" + kLimit)),
                 {"joint 'j2'", "damping"});
}

TEST(UrdfTest, RejectsRobotsWithoutMovingJoints) {
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + Joint("weld", "fixed", "base", "a", "")),
                 {"no revolute or continuous joint", "'base'"});
}

// ---- Warnings ----

// PUMA 560 link 3 as commonly tabulated (Armstrong et al. 1986): principal
// moments 0.066, 0.086, 0.0125 kg m², and 0.066 + 0.0125 < 0.086.
TEST(UrdfTest, WarnsAboutInertiasBreakingTheTriangleInequality) {
  const std::string puma = Robot(BareLink("base") + MassLink("link3", "4.4", "0.066 0 0 0.086 0 0.0125") +
                                 Joint("joint3", "revolute", "base", "link3"));
  const UrdfLoadResult loaded = LoadUrdfString(puma);
  EXPECT_EQ(loaded.model.link(0).inertia.I_Bcm_B(1, 1), 0.086);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("link 'link3'"), std::string::npos) << loaded.warnings[0];
  EXPECT_NE(loaded.warnings[0].find("triangle inequality"), std::string::npos) << loaded.warnings[0];

  // A <mimic> coupling is not modelled: the joint loads as independent.
  const UrdfLoadResult mimic = LoadUrdfString(
      Robot(BareLink("base") + MassLink("a") + MassLink("b") + Joint("j1", "revolute", "base", "a") +
            Joint("j2", "revolute", "a", "b", kLimit + "<mimic joint=\"j1\" multiplier=\"2\"/>")));
  EXPECT_EQ(mimic.model.n_links(), 2);
  ASSERT_EQ(mimic.warnings.size(), 1u);
  EXPECT_NE(mimic.warnings[0].find("joint 'j2'"), std::string::npos) << mimic.warnings[0];

  // A uniform rod has moments (0, I, I): on the boundary, no warning.
  const std::string rod = Robot(BareLink("base") + MassLink("rod", "1", "1e-12 0 0 0.5 0 0.5") +
                                Joint("j", "revolute", "base", "rod"));
  EXPECT_TRUE(LoadUrdfString(rod).warnings.empty());
}

// ---- Vendor URDFs: the chain, locked joints, inertia priors ----

// Parts held rigidly in a link frame B: mass, COM and inertia about it in B.

struct Part {
  double m;
  Eigen::Vector3d c;
  Eigen::Matrix3d I;
};

// Σ m, Σ m c / Σ m, Σ (I + m (|d|² 1 − d dᵀ)) with d = c − COM: the
// parallel-axis theorem written out again for the tests.
LinkInertia LumpByHand(const std::vector<Part>& parts) {
  LinkInertia total;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const Part& p : parts) {
    total.mass += p.m;
    moment += p.m * p.c;
  }
  total.p_BoBcm_B = moment / total.mass;
  for (const Part& p : parts) {
    const Eigen::Vector3d d = p.c - total.p_BoBcm_B;
    Eigen::Matrix3d shift;
    shift << d.y() * d.y() + d.z() * d.z(), -d.x() * d.y(), -d.x() * d.z(),  //
        -d.x() * d.y(), d.x() * d.x() + d.z() * d.z(), -d.y() * d.z(),       //
        -d.x() * d.z(), -d.y() * d.z(), d.x() * d.x() + d.y() * d.y();
    total.I_Bcm_B += p.I + p.m * shift;
  }
  return total;
}

// Panda link 7 with panda_link8, the hand and both fingers (open by q each)
// in link 7's frame, as testing::PandaLikeUrdf describes them.
LinkInertia PandaLink7ByHand(double q) {
  const Eigen::Matrix3d R = Rz(-kPi / 4);  // the hand in link 7
  const Eigen::Vector3d p_hand(0, 0, 0.107), p_fingers = p_hand + R * Eigen::Vector3d(0, 0, 0.0584);
  const auto rotated = [&R](double a, double b, double c) {
    return (R * Eigen::Vector3d(a, b, c).asDiagonal() * R.transpose()).eval();
  };
  return LumpByHand({
      {0.4, Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0.003, 0.003, 0.002).asDiagonal()},
      {0.73, p_hand + R * Eigen::Vector3d(-0.01, 0, 0.03), rotated(0.001, 0.0025, 0.0017)},
      {0.015, p_fingers + R * Eigen::Vector3d(0, q + 0.01, 0.02), rotated(2.375e-6, 2.375e-6, 7.5e-7)},
      {0.015, p_fingers + R * Eigen::Vector3d(0, -q - 0.01, 0.02), rotated(2.375e-6, 2.375e-6, 7.5e-7)},
  });
}

// Issue 12: the Panda's prismatic fingers (one a <mimic>) are locked at 0 and
// merged, with the hand and the fixed flange, into link 7: 7 joints, one
// warning naming both fingers; link 7 is what the parts lumped by hand give,
// and what the same file with the fingers on fixed joints gives.
TEST(UrdfTest, PandaFingersAreLockedAndMergedIntoTheLastLink) {
  const UrdfLoadResult loaded = LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf");
  const RobotModel& model = loaded.model;
  ASSERT_EQ(model.n_dof(), 7);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(model.link(i).joint_name, "panda_joint" + std::to_string(i + 1));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0],
                 {"panda.urdf: locked 2 joints", "'panda_link0' → 'panda_link7'",
                  "'panda_finger_joint1' (prismatic, at 0 m, into link 'panda_link7')",
                  "'panda_finger_joint2' (prismatic, mimics 'panda_finger_joint1', at 0 m, into link 'panda_link7')"});

  const LinkInertia expected = PandaLink7ByHand(0.0);
  const Link& link7 = model.link(6);
  ExpectNear(link7.inertia.mass, 1.16, 1e-15, "link 7 mass: 0.4 + 0.73 + 2 · 0.015 kg");
  ExpectNear(link7.inertia.p_BoBcm_B, expected.p_BoBcm_B, 1e-14, "link 7 COM");
  ExpectNear(link7.inertia.I_Bcm_B, expected.I_Bcm_B, 1e-12, "link 7 inertia");
  EXPECT_EQ(link7.shapes.size(), 3u);  // the hand's box and both fingers'

  const UrdfLoadResult fixed = LoadUrdfString(testing::PandaLikeUrdf(/*fingers_fixed=*/true, 0.0));
  EXPECT_TRUE(fixed.warnings.empty());
  ExpectModelsNear(model, fixed.model, 1e-12);
}

// --lock opens the fingers: finger 1 by the given 0.04 m along +y of the
// hand, finger 2 along −y by its <mimic> (multiplier 1): the lumped COM moves
// with them (by hand: 0.015 kg · 0.04 m · (±ŷ) cancel in the COM but not in
// the inertia).
TEST(UrdfTest, LockedFingersMoveToTheGivenOpening) {
  UrdfLoadOptions options;
  std::string why;
  ASSERT_TRUE(AddJointLock("panda_finger_joint1=0.04", &options, &why)) << why;
  const UrdfLoadResult loaded = LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf", "", options);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0], {"'panda_finger_joint1' (prismatic, at 0.04 m by locked_joints, into link 'panda_link7')",
                                      "'panda_finger_joint2' (prismatic, mimics 'panda_finger_joint1', at 0.04 m"});
  const LinkInertia open = PandaLink7ByHand(0.04), closed = PandaLink7ByHand(0.0);
  const Link& link7 = loaded.model.link(6);
  ExpectNear(link7.inertia.p_BoBcm_B, open.p_BoBcm_B, 1e-14, "link 7 COM, fingers open");
  ExpectNear(link7.inertia.I_Bcm_B, open.I_Bcm_B, 1e-12, "link 7 inertia, fingers open");
  // Opening both fingers by 0.04 m adds 2 · 0.015 · (0.05² − 0.01²) to the
  // moments about the hand's x and z (Rz(−π/4) mixes x and y of link 7).
  EXPECT_NEAR(link7.inertia.I_Bcm_B(2, 2) - LoadUrdfString(testing::PandaLikeUrdf()).model.link(6).inertia.I_Bcm_B(2, 2),
              2 * 0.015 * (0.05 * 0.05 - 0.01 * 0.01), 1e-15);
  ExpectNear(open.p_BoBcm_B, closed.p_BoBcm_B, 1e-14, "symmetric fingers keep the COM");
  ExpectModelsNear(loaded.model, LoadUrdfString(testing::PandaLikeUrdf(true, 0.04)).model, 1e-12);

  // Finger 1 alone (finger 2 held closed by its own --lock): the COM moves
  // by 0.015 · 0.04 / 1.16 m along the hand's +y.
  ASSERT_TRUE(AddJointLock("panda_finger_joint2=0", &options, &why)) << why;
  const Link one = LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf", "", options).model.link(6);
  ExpectNear(one.inertia.p_BoBcm_B, (closed.p_BoBcm_B + Rz(-kPi / 4) * Eigen::Vector3d(0, 0.015 * 0.04 / 1.16, 0)).eval(),
             1e-14, "link 7 COM, finger 1 open");
}

// --tip ends the chain early and --lock holds a chain joint: everything
// below is merged into the new last link.
TEST(UrdfTest, TipAndLockShortenTheChain) {
  const LinkInertia hand = PandaLink7ByHand(0.0);
  UrdfLoadOptions tip5;
  tip5.tip_link = "panda_link5";
  UrdfLoadResult short_arm = LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf", "", tip5);
  short_arm.warnings = WithoutGeometryWarnings(short_arm.warnings);  // the fixture's shapes are placed freely
  ASSERT_EQ(short_arm.model.n_dof(), 5);
  EXPECT_NEAR(short_arm.model.link(4).inertia.mass, 1 + 1 + hand.mass, 1e-14);  // links 5, 6, 7 and the hand
  ASSERT_EQ(short_arm.warnings.size(), 1u);
  ExpectContains(short_arm.warnings[0], {"locked 4 joints", "'panda_link0' → 'panda_link5'",
                                         "'panda_joint6' (revolute, at 0 rad, into link 'panda_link5')",
                                         "'panda_joint7' (revolute, at 0 rad, into link 'panda_link5')"});
  // A tip among links held rigidly changes nothing but the warning's chain.
  UrdfLoadOptions tip_hand;
  tip_hand.tip_link = "panda_hand";
  ExpectModelsNear(LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf", "", tip_hand).model,
                   LoadUrdfString(testing::PandaLikeUrdf()).model, 0.0);

  // Joint 7 locked at 0.5 rad: link 6 carries link 7, turned about z.
  UrdfLoadOptions lock7;
  lock7.locked_joints["panda_joint7"] = 0.5;
  const UrdfLoadResult six = LoadUrdfString(testing::PandaLikeUrdf(), "panda.urdf", "", lock7);
  ASSERT_EQ(six.model.n_dof(), 6);
  ExpectContains(six.warnings.at(0), {"'panda_joint7' (revolute, at 0.5 rad by locked_joints, into link 'panda_link6')"});
  // Link 7's frame in link 6: (0.088, 0, 0), Rx(π/2)·Rz(0.5); link 6 is 1 kg at its origin.
  const Eigen::Vector3d p_67(0.088, 0, 0);
  const Eigen::Matrix3d R_67 = Rx(kPi / 2) * Rz(0.5);
  const LinkInertia expected = LumpByHand({{1.0, Eigen::Vector3d::Zero(), 0.1 * Eigen::Matrix3d::Identity()},
                                           {hand.mass, p_67 + R_67 * hand.p_BoBcm_B, R_67 * hand.I_Bcm_B * R_67.transpose()}});
  ExpectNear(six.model.link(5).inertia.mass, expected.mass, 1e-15, "link 6 mass");
  ExpectNear(six.model.link(5).inertia.p_BoBcm_B, expected.p_BoBcm_B, 1e-14, "link 6 COM");
  ExpectNear(six.model.link(5).inertia.I_Bcm_B, expected.I_Bcm_B, 1e-12, "link 6 inertia");
}

TEST(UrdfTest, OptionsThatDoNotFitTheFileAreRefusedNamingWhatToChange) {
  const std::string panda = testing::PandaLikeUrdf();
  ExpectRejectedWith(panda, Options({{"panda_finger_joint1", 0.05}}),
                     {"locked_joints panda_finger_joint1=0.05", "outside the <limit>", "[0, 0.04] m"});
  ExpectRejectedWith(panda, Options({{"wrist", 0.0}}),
                     {"no joint 'wrist'", "joints that can be locked: 'panda_finger_joint1', 'panda_finger_joint2', "
                                          "'panda_joint1'"});
  ExpectRejectedWith(panda, Options({{"panda_hand_joint", 0.0}}), {"'panda_hand_joint' is fixed already"});
  ExpectRejectedWith(panda, Options({}, "flange"), {"tip_link flange: no link 'flange'", "'panda_hand'"});
  ExpectRejectedWith(panda, Options({}, "panda_link0"), {"root link"});
  ExpectRejectedWith(panda, Options({}, "panda_leftfinger"),
                     {"joint 'panda_finger_joint1': prismatic joint on the chain", "locked_joints panda_finger_joint1=VALUE"});

  // AddJointLock parses JOINT=VALUE.
  UrdfLoadOptions options;
  std::string why;
  EXPECT_TRUE(AddJointLock("j=-1.5e-1", &options, &why));
  EXPECT_EQ(options.locked_joints.at("j"), -0.15);
  for (const std::string bad : {"j", "=1", "k=", "k=1x", "k=inf", "j=2"}) {
    EXPECT_FALSE(AddJointLock(bad, &options, &why)) << bad;
    EXPECT_NE(why.find("'" + bad + "'"), std::string::npos) << why;
  }
}

// Two revolute chains from one link: the message names the fork and both
// ends; --tip picks one, and the other branch is locked into the fork.
TEST(UrdfTest, BranchesAskForATipAndTheOtherBranchIsMerged) {
  const std::string xml =
      Robot(BareLink("base") + MassLink("a") + MassLink("b") + MassLink("b2") +
            "<link name=\"c\"><inertial><origin xyz=\"0 0.2 0\"/><mass value=\"0.5\"/><inertia ixx=\"0.01\" "
            "ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>" +
            Joint("j1", "revolute", "base", "a") + Joint("j2", "revolute", "a", "b") +
            Joint("j3", "revolute", "b", "b2") +
            Joint("j4", "revolute", "a", "c", "<origin xyz=\"0.3 0 0\"/><axis xyz=\"1 0 0\"/>" + kLimit));
  ExpectRejectedWith(xml, {}, {"link 'a': the robot branches into 2 chains", "'b2' (joint 'j3')", "'c' (joint 'j4')",
                               "tip_link LINK"});
  const UrdfLoadResult loaded = LoadUrdfString(xml, "vendor.urdf", "", Options({}, "b2"));
  ASSERT_EQ(loaded.model.n_dof(), 3);
  // a (1 kg at 0) with c (0.5 kg at (0.3, 0.2, 0)): COM (0.1, 0.2/3, 0).
  const LinkInertia expected = LumpByHand({{1.0, Eigen::Vector3d::Zero(), 0.1 * Eigen::Matrix3d::Identity()},
                                           {0.5, Eigen::Vector3d(0.3, 0.2, 0), 0.01 * Eigen::Matrix3d::Identity()}});
  ExpectNear(loaded.model.link(0).inertia.p_BoBcm_B, Eigen::Vector3d(0.1, 0.2 / 3, 0), 1e-15, "a's COM");
  ExpectNear(loaded.model.link(0).inertia.I_Bcm_B, expected.I_Bcm_B, 1e-14, "a's inertia");
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0], {"'j4' (revolute, at 0 rad, into link 'a')"});
  // The other end, with a --lock turning c by 1 rad about x: (0.3, 0.2 cos 1, 0.2 sin 1).
  const UrdfLoadResult other =
      LoadUrdfString(xml, "vendor.urdf", "", Options({{"j4", 1.0}}, "a"));
  ASSERT_EQ(other.model.n_dof(), 1);
  ExpectNear(other.model.link(0).inertia.mass, 1 + 1 + 1 + 0.5, 1e-15, "a with b, b2 and c");
  ExpectContains(other.warnings.at(0), {"locked 3 joints"});
}

// Issue 12: the TX40's link_6, 0.2 kg with an all-zero inertia (a point
// mass), loads with one warning naming it: its moments become those of a
// 1 cm uniform sphere of 0.2 kg, 0.4 · 0.2 · 0.01² = 8e-6 kg m², and Bullet
// realises the commanded accelerations of the result.
TEST(UrdfTest, PointMassInertiaLoadsWithAPriorAndSimulates) {
  std::string body = BareLink("base_link");
  for (int i = 1; i <= 6; ++i) {
    const std::string parent = i == 1 ? "base_link" : "link_" + std::to_string(i - 1);
    body += (i < 6 ? MassLink("link_" + std::to_string(i), "2", "0.02 0 0 0.03 0 0.025")
                   : MassLink("link_6", "0.2", "0 0 0 0 0 0")) +
            Joint("joint_" + std::to_string(i), "revolute", parent, "link_" + std::to_string(i),
                  "<origin xyz=\"0 0.05 0.2\" rpy=\"" + std::to_string(i % 2 ? 1.5707963267948966 : 0.0) +
                      " 0 0\"/>" + kLimit);
  }
  const UrdfLoadResult loaded = LoadUrdfString(Robot(body), "tx40.urdf");
  ASSERT_EQ(loaded.model.n_dof(), 6);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0], {"tx40.urdf: link 'link_6': mass 0.2 kg", "not positive definite",
                                      "principal moments about its centre of mass 0, 0, 0 kg m²", "only a prior",
                                      "raised to it: 8e-06, 8e-06, 8e-06 kg m²"});
  ExpectNear(loaded.model.link(5).inertia.I_Bcm_B, (8e-6 * Eigen::Matrix3d::Identity()).eval(), 1e-15, "link_6 prior");
  ExpectNear(loaded.model.link(5).inertia.mass, 0.2, 0.0, "link_6 mass");

  BulletSimulation sim(loaded.model);
  RobotData data(loaded.model);
  std::mt19937 rng(12);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = testing::RandomVector(6, 1.0, &rng), qd = testing::RandomVector(6, 1.0, &rng),
                          qdd = testing::RandomVector(6, 4.0, &rng);
    sim.SetState(q, qd);
    sim.Step(InverseDynamics(loaded.model, q, qd, qdd, &data), 1e-3);
    Eigen::VectorXd q1, qd1;
    sim.GetState(&q1, &qd1);
    EXPECT_LT(testing::RelativeError((qd1 - qd) / 1e-3, qdd), 1e-8) << "trial " << trial;
  }
}

// A rod (moments 0, I, I, turned) keeps its axes and its two moments; the
// zero one is raised to the sphere's 0.4 m r².
TEST(UrdfTest, SemidefiniteInertiaKeepsItsAxesAndLargeMoments) {
  const Eigen::Matrix3d R = Rz(0.3) * Ry(0.7);
  const Eigen::Matrix3d I_rod = R * Eigen::Vector3d(0, 0.02, 0.02).asDiagonal() * R.transpose();
  std::ostringstream inertia;
  inertia.precision(17);
  inertia << I_rod(0, 0) << " " << I_rod(0, 1) << " " << I_rod(0, 2) << " " << I_rod(1, 1) << " " << I_rod(1, 2) << " "
          << I_rod(2, 2);
  const UrdfLoadResult loaded = LoadUrdfString(
      Robot(BareLink("base") + MassLink("rod", "3", inertia.str()) + Joint("j", "revolute", "base", "rod")));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0], {"link 'rod'", "raised to it: 0.00012, 0.02, 0.02 kg m²"});
  const Eigen::Matrix3d expected = R * Eigen::Vector3d(0.4 * 3 * 1e-4, 0.02, 0.02).asDiagonal() * R.transpose();
  ExpectNear(loaded.model.link(0).inertia.I_Bcm_B, expected, 1e-13, "rod prior");
}

// The KUKA LWR4+ file FloBaRoID ships (../shared/data): 7 joints with the
// file's masses, nothing locked, one warning for its missing collision mesh.
TEST(UrdfTest, KukaLwr4LoadsAsBefore) {
  const std::filesystem::path path = std::filesystem::path(IDBENCH_SOURCE_DIR) /
                                     "../shared/data/kuka_lwr4/lwr_description/urdf/kuka_lwr4.urdf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (../shared is not beside the checkout)";
  const UrdfLoadResult loaded = LoadUrdfFile(path.string());
  ASSERT_EQ(loaded.model.n_dof(), 7);
  const double masses[7] = {2.7, 2.7, 2.7, 2.7, 1.7, 1.6, 0.3};  // <mass> of lwr_1_link .. lwr_7_link
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(loaded.model.link(i).joint_name, "lwr_" + std::to_string(i) + "_joint");
    EXPECT_EQ(loaded.model.link(i).inertia.mass, masses[i]) << i;
  }
  ASSERT_EQ(loaded.warnings.size(), 1u);
  ExpectContains(loaded.warnings[0], {"arm_wrist_convex.stl", "shape skipped"});
}

// ---- Hostile and broken files (issue 14) ----

// A long chain is walked without recursion: 20 000 links on fixed joints
// below the one revolute joint load as one lumped link of 20 001 kg.
TEST(UrdfTest, LongChainsLoadWithoutDeepRecursion) {
  std::string body = BareLink("base") + MassLink("l0") + Joint("j", "continuous", "base", "l0", "");
  constexpr int kLinks = 20000;
  for (int k = 1; k <= kLinks; ++k) {
    const std::string name = "l" + std::to_string(k), parent = "l" + std::to_string(k - 1);
    body += MassLink(name) + Joint("f" + std::to_string(k), "fixed", parent, name, "");
  }
  const RobotModel model = LoadUrdfString(Robot(body)).model;
  ASSERT_EQ(model.n_links(), 1);
  EXPECT_EQ(model.link(0).inertia.mass, kLinks + 1.0);
}

}  // namespace
}  // namespace idbench
