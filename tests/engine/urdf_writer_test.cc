#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "engine/urdf_test_util.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Round trips ----

TEST(UrdfTest, RoundTripReproducesPaper6r) {
  const RobotModel expected = MakePaper6r();
  const UrdfLoadResult loaded = LoadUrdfString(WriteUrdf(expected));
  EXPECT_TRUE(loaded.warnings.empty());
  ExpectModelsNear(loaded.model, expected, 1e-12);
}

// The tilted robot with every URDF-expressible field set: finite and
// infinite limits, friction, all three shape kinds at random poses, and a
// rotor inertia, which URDF cannot carry and is dropped.
TEST(UrdfTest, RoundTripReproducesTiltedRobotWithLimitsFrictionAndShapes) {
  std::vector<Link> links = testing::MakeTiltedRobot().links();
  std::mt19937 rng(11);
  const auto random_pose = [&rng] {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(Eigen::Vector4d(testing::RandomVector(4, 1.0, &rng)).normalized())
                     .toRotationMatrix();
    X.translation() = testing::RandomVector(3, 0.5, &rng);
    return X;
  };
  links[0].limits = {-2.5, 1.5, 3.0, kInf, 40.0};
  links[1].limits = {-1.0, 2.0, kInf, kInf, 25.0};
  links[2].limits = {-kInf, kInf, 4.0, kInf, kInf};  // continuous with a velocity limit
  links[0].dynamics = {0.3, 0.1, 0.02};
  links[3].dynamics = {0.0, 0.7, 0.0};
  links[0].shapes.push_back({Shape::Kind::kCylinder, {0.05, 0.05, 0.4}, random_pose(), nullptr, ""});
  links[1].shapes.push_back({Shape::Kind::kBox, {0.1, 0.2, 0.3}, random_pose(), nullptr, ""});
  links[1].shapes.push_back({Shape::Kind::kSphere, {0.07, 0.07, 0.07}, random_pose(), nullptr, ""});
  links[3].X_PJ.linear() = Ry(kPi / 2) * Rx(0.3);  // gimbal lock in the joint origin
  const RobotModel expected("tilted4r", links);

  UrdfLoadResult loaded = LoadUrdfString(WriteUrdf(expected));
  loaded.warnings = WithoutGeometryWarnings(loaded.warnings);  // the shapes are at random poses
  // A·Aᵀ + 0.2·1 need not be a rigid body's inertia: each link whose principal
  // moments break a + b ≥ c gets a warning naming it.
  std::vector<std::string> violators;
  for (const Link& link : expected.links()) {
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(link.inertia.I_Bcm_B).eigenvalues();
    if (moments[0] + moments[1] < moments[2]) violators.push_back("link '" + link.name + "'");
  }
  ASSERT_EQ(loaded.warnings.size(), violators.size());
  for (size_t k = 0; k < violators.size(); ++k) {
    EXPECT_NE(loaded.warnings[k].find(violators[k]), std::string::npos) << loaded.warnings[k];
  }
  // MakeTiltedRobot leaves joint names empty; the writer makes them up.
  ExpectModelsNear(loaded.model, expected, 1e-12, /*compare_joint_names=*/false);
  for (const Link& link : loaded.model.links()) EXPECT_EQ(link.joint_name, link.name + "_joint");
  EXPECT_EQ(loaded.model.link(0).dynamics.rotor_inertia, 0.0);
}

// Names URDF would choke on are escaped, and a link called "base" pushes the
// ground link to another name.
TEST(UrdfTest, WriterEscapesNamesAndKeepsTheGroundNameUnique) {
  std::vector<Link> links = MakePaper6r().links();
  links[0].name = "base";
  links[1].name = "world";
  links[2].joint_name = "a<b>&\"c'";
  const RobotModel expected("r&d <robot>", links);
  const std::string xml = WriteUrdf(expected);
  EXPECT_NE(xml.find("<link name=\"world_1\"/>"), std::string::npos) << xml;
  ExpectModelsNear(LoadUrdfString(xml).model, expected, 1e-12);
}

// The ground links (a table, a pedestal: issue 35) are written as fixed
// links under the root and read back with the same shapes where they were.
TEST(UrdfTest, RoundTripKeepsTheGroundLinks) {
  const RobotModel expected = LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf").model;
  const RobotModel loaded = LoadUrdfString(WriteUrdf(expected)).model;
  ExpectModelsNear(loaded, expected, 1e-12);
  ASSERT_EQ(loaded.ground().size(), expected.ground().size());
  for (const GroundLink& b : expected.ground()) {  // urdfdom orders the root's children by joint name
    const auto same = [&](const GroundLink& g) { return g.name == b.name; };
    const auto found = std::find_if(loaded.ground().begin(), loaded.ground().end(), same);
    ASSERT_NE(found, loaded.ground().end()) << b.name;
    const GroundLink& a = *found;
    ASSERT_EQ(a.CollisionShapes().size(), b.CollisionShapes().size()) << b.name;
    for (size_t k = 0; k < b.CollisionShapes().size(); ++k) {
      EXPECT_EQ(a.CollisionShapes()[k].kind, b.CollisionShapes()[k].kind) << b.name;
      EXPECT_TRUE(a.CollisionShapes()[k].size.isApprox(b.CollisionShapes()[k].size, 1e-12)) << b.name;
      EXPECT_TRUE(a.CollisionShapes()[k].X_BG.isApprox(b.CollisionShapes()[k].X_BG, 1e-12)) << b.name;
    }
  }
}

TEST(UrdfTest, WriterRejectsOneSidedLimits) {
  std::vector<Link> links = MakePaper6r().links();
  links[4].limits.q_max = 1.0;
  try {
    WriteUrdf(RobotModel("one_sided", links));
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("link 'B5'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace idbench
