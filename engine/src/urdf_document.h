// Checks on a URDF's XML before urdfdom reads it, each naming the line: the
// text is XML with a <robot> root; every number urdfdom reads is one finite
// number of the right sign (urdfdom drops an element it cannot parse and
// loads the rest, and takes NaN, inf and negative limits); the joints form a
// tree (no link hangs from two joints, no loop), so that walking the links
// from the root ends.
#pragma once

#include <string>

namespace idbench::internal {

// Throws std::invalid_argument "SOURCE:LINE: link 'a': ..." (or "SOURCE: not
// XML (line L, column C: ...)") for the first problem found.
void CheckUrdfDocument(const std::string& xml, const std::string& source_name);

}  // namespace idbench::internal
