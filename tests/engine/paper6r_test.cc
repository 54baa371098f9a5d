#include "idbench/engine/paper6r.h"

#include <gtest/gtest.h>

namespace idbench {
namespace {

// Paper Table 1 (printed to 4 decimals): m, J11, J22 (= J33).
constexpr double kTable1[6][3] = {
    {6402.6012, 800.3251, 982.8126}, {2746.0726, 123.5733, 416.4934}, {1186.1661, 23.7233, 156.5838},
    {308.7953, 6.1759, 5.6413},      {284.2877, 5.6858, 4.8353},      {661.7042, 29.7767, 19.8511}};

TEST(Paper6rTest, MassesAndInertiasMatchTable1) {
  const RobotModel model = MakePaper6r();
  ASSERT_EQ(model.n_links(), 6);
  for (int i = 0; i < 6; ++i) {
    const LinkInertia& inertia = model.link(i).inertia;
    EXPECT_NEAR(inertia.mass, kTable1[i][0], 5e-5) << "B" << i + 1;
    EXPECT_NEAR(inertia.I_Bcm_B(0, 0), kTable1[i][1], 5e-5) << "B" << i + 1;
    EXPECT_NEAR(inertia.I_Bcm_B(1, 1), kTable1[i][2], 5e-5) << "B" << i + 1;
    EXPECT_NEAR(inertia.I_Bcm_B(2, 2), kTable1[i][2], 5e-5) << "B" << i + 1;
  }
}

TEST(Paper6rTest, SerialChainWithHingesAtCylinderEnds) {
  const RobotModel model = MakePaper6r();
  const Paper6rGeometry geometry;
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(model.link(i).parent, i - 1);
    EXPECT_DOUBLE_EQ(model.link(i).inertia.p_BoBcm_B.x(), geometry.length[static_cast<size_t>(i)] / 2);
    if (i > 0) {
      EXPECT_DOUBLE_EQ(model.link(i).X_PJ.translation().x(), geometry.length[static_cast<size_t>(i - 1)]);
    }
  }
}

}  // namespace
}  // namespace idbench
