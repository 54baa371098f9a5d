// The ROS 2 bag fixtures of tests/data/bags (written by their own script there).
#pragma once

#include <filesystem>

namespace idbench::testing {

inline const std::filesystem::path kBags = std::filesystem::path(IDBENCH_SOURCE_DIR) / "tests" / "data" / "bags";

}  // namespace idbench::testing
