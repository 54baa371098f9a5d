// The time axis of a plot: pixel ↔ time, and the window a drag selects.
#include "idbench/gui/time_axis.h"

#include <gtest/gtest.h>

namespace idbench::gui {
namespace {

TEST(TimeAxisTest, MapsPixelsToTimesLinearlyAndBack) {
  const TimeAxis axis{.x0 = 100.0, .x1 = 600.0, .t0 = 2.0, .t1 = 12.0};  // 50 px per second
  EXPECT_DOUBLE_EQ(axis.TimeAt(100.0), 2.0);
  EXPECT_DOUBLE_EQ(axis.TimeAt(600.0), 12.0);
  EXPECT_DOUBLE_EQ(axis.TimeAt(350.0), 7.0);
  EXPECT_DOUBLE_EQ(axis.TimeAt(125.0), 2.5);
  EXPECT_DOUBLE_EQ(axis.TimeAt(20.0), 2.0);   // clamped to the plot
  EXPECT_DOUBLE_EQ(axis.TimeAt(900.0), 12.0);
  for (double t : {2.0, 3.3, 7.0, 11.99}) EXPECT_NEAR(axis.TimeAt(axis.PixelAt(t)), t, 1e-12);
  EXPECT_DOUBLE_EQ(axis.PixelAt(4.0), 200.0);
}

TEST(TimeAxisTest, ADragSelectsTheWindowInEitherDirection) {
  const TimeAxis axis{.x0 = 100.0, .x1 = 600.0, .t0 = 2.0, .t1 = 12.0};
  EXPECT_EQ(DraggedTimeWindow(axis, 150.0, 400.0), (std::vector<double>{3.0, 8.0}));
  EXPECT_EQ(DraggedTimeWindow(axis, 400.0, 150.0), (std::vector<double>{3.0, 8.0}));
  EXPECT_EQ(DraggedTimeWindow(axis, 50.0, 700.0), (std::vector<double>{2.0, 12.0}));  // past the edges
  // A click (less than 3 px) clears the window: the whole log.
  EXPECT_TRUE(DraggedTimeWindow(axis, 300.0, 302.0).empty());
  EXPECT_EQ(DraggedTimeWindow(axis, 300.0, 303.0).size(), 2u);
  // Outside the plot on one side: nothing between.
  EXPECT_TRUE(DraggedTimeWindow(axis, 620.0, 700.0).empty());
}

}  // namespace
}  // namespace idbench::gui
