// The robot's cell (--scene FILE), in SI units, poses in the world frame as
// [x, y, z, roll, pitch, yaw] (URDF's fixed-axis rpy):
//   {"floor": true,
//    "obstacles": [{"type": "box", "size": [2.0, 2.0, 0.05], "pose": [0, 0, -0.026, 0, 0, 0]},
//                  {"type": "cylinder", "radius": 0.1, "length": 1.0, "pose": [...]},
//                  {"type": "sphere", "radius": 0.2, "pose": [...]},
//                  {"type": "mesh", "path": "fixture.stl", "scale": [1, 1, 1], "pose": [...]}]}
// "floor" (default true) and "obstacles" (default none; at most
// Cell::kMaxObstacles) are optional; each obstacle may have a "name". A
// pose is required; a mesh's path is relative to the scene file; "scale"
// defaults to 1. Unknown keys are refused.
#pragma once

#include <string>

#include "idbench/engine/cell.h"

namespace idbench {

// Throws std::invalid_argument "source: .obstacles[2].radius: what" for
// invalid JSON, an unknown key, a missing or mistyped field, a size ≤ 0, a
// mesh that cannot be read, more obstacles than Cell::kMaxObstacles.
// base_dir: where relative mesh paths start.
Cell ParseSceneJson(const std::string& text, const std::string& source, const std::string& base_dir);

// Reads and parses a scene file; an unreadable file throws naming the path.
Cell ReadSceneFile(const std::string& path);

}  // namespace idbench
