#include "idbench/workbench/reports/message_list.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace idbench {
namespace {

std::string MissingMesh(const std::string& link) {
  return "kuka.urdf: link '" + link + "': mesh 'package://lwr/meshes/" + link + ".stl' not found (looked in /a/" +
         link + ".stl, /b/" + link + ".stl; set ROS_PACKAGE_PATH for package:// names); shape skipped";
}

// One warning per missing mesh becomes one line with the count and the other
// links named; a different warning keeps its place after it.
TEST(MessageListTest, MissingMeshesCollapseIntoOneWithACount) {
  std::vector<std::string> messages;
  for (int k = 1; k <= 7; ++k) messages.push_back(MissingMesh("l" + std::to_string(k)));
  messages.insert(messages.begin() + 2, "kuka.urdf: joint 'j2': <mimic> ignored; the joint is loaded as independent");
  const std::vector<std::string> collapsed = CollapseRepeatedMessages(messages);
  ASSERT_EQ(collapsed.size(), 2u);
  EXPECT_EQ(collapsed[0], MissingMesh("l1") + " (and 6 more like it: 'l2', 'l3', 'l4', 'l5', …)");
  EXPECT_EQ(collapsed[1], messages[2]);
}

TEST(MessageListTest, IdenticalMessagesCountAndDistinctOnesStay) {
  const std::vector<std::string> collapsed =
      CollapseRepeatedMessages({"log.csv: no joint moves", "log.csv: no joint moves", "log.csv: other"});
  ASSERT_EQ(collapsed.size(), 2u);
  EXPECT_EQ(collapsed[0], "log.csv: no joint moves (and 1 more like it)");
  EXPECT_EQ(collapsed[1], "log.csv: other");
  EXPECT_TRUE(CollapseRepeatedMessages({}).empty());
  // Different words outside quotes and parentheses: not alike.
  EXPECT_EQ(CollapseRepeatedMessages({"link 'a': mass raised", "link 'b': inertia raised"}).size(), 2u);
  // An apostrophe inside a word is no quote.
  EXPECT_EQ(MessageShape("don't move 'q1' (a)"), "don't move '…' (…)");
}

}  // namespace
}  // namespace idbench
