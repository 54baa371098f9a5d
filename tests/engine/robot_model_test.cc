#include "idbench/engine/robot_model.h"

#include <gtest/gtest.h>

#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

std::vector<Link> PaperLinks() { return MakePaper6r().links(); }

void ExpectModelRejected(std::vector<Link> links, const std::string& fragment) {
  try {
    RobotModel model("broken", std::move(links));
    FAIL() << "expected std::invalid_argument containing '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(RobotModelTest, RejectsBrokenLinksNamingThem) {
  auto links = PaperLinks();
  links[2].inertia.mass = 0.0;
  ExpectModelRejected(links, "link 'B3': mass must be > 0");

  links = PaperLinks();
  links[4].inertia.I_Bcm_B(1, 1) = -1.0;
  ExpectModelRejected(links, "link 'B5': inertia tensor must be positive definite");

  links = PaperLinks();
  links[1].limits.q_min = 1.0;
  links[1].limits.q_max = 0.0;
  ExpectModelRejected(links, "link 'B2': joint limits");

  links = PaperLinks();
  links[3].parent = 3;
  ExpectModelRejected(links, "link 'B4': parent index");

  links = PaperLinks();
  links[0].axis_J = Eigen::Vector3d(1, 1, 0);
  ExpectModelRejected(links, "link 'B1': joint axis");

  ExpectModelRejected({}, "no links");
}

TEST(RobotModelTest, ChildrenFollowParents) {
  const RobotModel model = MakePaper6r();
  EXPECT_EQ(model.children(-1), std::vector<int>{0});
  EXPECT_EQ(model.children(2), std::vector<int>{3});
  EXPECT_TRUE(model.children(5).empty());
}

}  // namespace
}  // namespace idbench
