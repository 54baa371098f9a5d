// The messages a person reads in a list (a report's warnings, the GUI's
// Messages panel): repeated ones collapsed into one with a count, so that a
// robot file with 30 missing meshes says so once.
#pragma once

#include <string>
#include <vector>

namespace idbench {

// The messages in their order of first appearance, each group of alike
// messages as its first one followed by "(and N more like it: 'a', 'b', …)",
// naming the first quoted word of each of the others (at most
// kMaxNamedOthers, then "…"). Alike: equal once every quoted part ('…') and
// every parenthesised part ((…), nested or not) is set aside, so "link 'l1':
// mesh 'a.stl' not found (looked in /x)" and the same for 'l2' and 'b.stl' are
// alike; identical messages are too.
std::vector<std::string> CollapseRepeatedMessages(const std::vector<std::string>& messages);

inline constexpr int kMaxNamedOthers = 4;

// The part of `message` alike messages share (see CollapseRepeatedMessages).
std::string MessageShape(const std::string& message);

}  // namespace idbench
