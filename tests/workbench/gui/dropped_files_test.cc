// Routing of files dropped onto the window: by kind, into the log and the
// held-out log in order, Shift sending a log to the held-out one, and a
// message naming a file that is neither a robot nor a log.
#include "idbench/gui/dropped_files.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace idbench::gui {
namespace {

using Target = DroppedFileRoute::Target;

std::vector<Target> Targets(const std::vector<DroppedFileRoute>& routes) {
  std::vector<Target> targets;
  for (const DroppedFileRoute& route : routes) targets.push_back(route.target);
  return targets;
}

TEST(DroppedFilesTest, ClassifiesByWhatThePathIs) {
  EXPECT_EQ(ClassifyDroppedPath("/robots/arm.urdf"), DroppedKind::kRobot);
  EXPECT_EQ(ClassifyDroppedPath("arm.URDF"), DroppedKind::kRobot);
  EXPECT_EQ(ClassifyDroppedPath("arm.urdf.xacro"), DroppedKind::kRobot);
  EXPECT_EQ(ClassifyDroppedPath("/logs/run 1.csv"), DroppedKind::kLog);
  EXPECT_EQ(ClassifyDroppedPath("run.CSV"), DroppedKind::kLog);
  EXPECT_EQ(ClassifyDroppedPath("run.db3"), DroppedKind::kLog);
  EXPECT_EQ(ClassifyDroppedPath("run.mcap"), DroppedKind::kLog);
  EXPECT_EQ(ClassifyDroppedPath("description.yaml"), DroppedKind::kLog);
  // A bag folder: a directory holding metadata.yaml, whatever its name.
  EXPECT_EQ(ClassifyDroppedPath(std::string(IDBENCH_SOURCE_DIR) + "/tests/data/bags/bag_db3"), DroppedKind::kLog);
  EXPECT_EQ(ClassifyDroppedPath(std::string(IDBENCH_SOURCE_DIR) + "/tests/data"), DroppedKind::kOther);
  EXPECT_EQ(ClassifyDroppedPath("picture.png"), DroppedKind::kOther);
  EXPECT_EQ(ClassifyDroppedPath("README"), DroppedKind::kOther);
}

TEST(DroppedFilesTest, RoutesLogsInOrderAndRobotsToTheRobot) {
  const std::vector<DroppedFileRoute> routes =
      RouteDroppedFiles({"a.csv", "arm.urdf", "b.csv", "c.csv", "notes.pdf"}, /*data_set=*/false, /*held_out=*/false);
  EXPECT_EQ(Targets(routes),
            (std::vector<Target>{Target::kData, Target::kRobot, Target::kValidate, Target::kNone, Target::kNone}));
  EXPECT_EQ(routes[0].path, "a.csv");
  EXPECT_EQ(routes[2].path, "b.csv");
  // The third log and the PDF say why nothing was done, naming the file.
  EXPECT_NE(routes[3].message.find("'c.csv'"), std::string::npos) << routes[3].message;
  EXPECT_NE(routes[4].message.find("'notes.pdf'"), std::string::npos) << routes[4].message;
  EXPECT_NE(routes[4].message.find(".urdf"), std::string::npos) << routes[4].message;
  EXPECT_NE(routes[4].message.find(".csv"), std::string::npos) << routes[4].message;
}

TEST(DroppedFilesTest, ShiftSendsALogToTheHeldOutLogOnlyWhenALogIsSet) {
  // A log set: without Shift the drop replaces it, with Shift it is the held-out one.
  EXPECT_EQ(Targets(RouteDroppedFiles({"b.csv"}, true, false)), std::vector<Target>{Target::kData});
  EXPECT_EQ(Targets(RouteDroppedFiles({"b.csv"}, true, true)), std::vector<Target>{Target::kValidate});
  EXPECT_EQ(Targets(RouteDroppedFiles({"b.csv", "c.csv"}, true, true)),
            (std::vector<Target>{Target::kValidate, Target::kNone}));
  // No log yet: Shift changes nothing (the log comes first).
  EXPECT_EQ(Targets(RouteDroppedFiles({"b.csv"}, false, true)), std::vector<Target>{Target::kData});
  // Robots go to the robot with or without Shift.
  EXPECT_EQ(Targets(RouteDroppedFiles({"arm.urdf"}, true, true)), std::vector<Target>{Target::kRobot});
  EXPECT_TRUE(RouteDroppedFiles({}, false, false).empty());
}

}  // namespace
}  // namespace idbench::gui
