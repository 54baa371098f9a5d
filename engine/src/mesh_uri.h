// Where a URDF <mesh filename> is on disk (internal to engine/src).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace idbench::internal {

// The file a URDF <mesh filename> names:
//   package://P/rest → D/P/rest for each D in ROS_PACKAGE_PATH (':'-separated);
//     then, walking up from the URDF's directory, A/rest for an ancestor A
//     named P, or A/P/rest (a package next to or above the URDF);
//   file:///abs → /abs; an absolute path as is; a relative path against the
//   URDF's directory.
// The first candidate that exists (a regular file or not: LoadTriangleMesh
// says what is wrong with it); nullopt otherwise, with every candidate in
// *looked.
std::optional<std::filesystem::path> ResolveMeshUri(const std::string& uri, const std::filesystem::path& base_directory,
                                                    std::vector<std::string>* looked);

}  // namespace idbench::internal
