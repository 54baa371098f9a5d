// From a parsed URDF to a RobotModel (internal to engine/src): choosing the
// chain of degrees of freedom, locking the joints off it and lumping the
// links held rigidly to a chain link into it, reading joints, inertials and
// shapes (UrdfShapeReader, urdf_shape_reader.h).
#pragma once

#include <urdf_model/model.h>

#include <filesystem>
#include <string>

#include "idbench/engine/urdf.h"

namespace idbench::internal {

// The model and warnings LoadUrdfString (urdf.h) describes, of a urdfdom tree
// read from `source` (the name messages start with); relative mesh paths
// start at base_directory. Throws std::invalid_argument "SOURCE: ..." as
// LoadUrdfString says.
UrdfLoadResult BuildUrdfChain(const urdf::ModelInterface& urdf, const std::string& source,
                              const std::filesystem::path& base_directory, const UrdfLoadOptions& options);

}  // namespace idbench::internal
