// ros_control <transmission> elements of a URDF (read beside urdfdom, which
// skips them): the reductions of the chain's joints.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/transmission.h"

namespace idbench::internal {

// Every <transmission> whose <joint> is one of model's joints, of type
// SimpleTransmission (<type>…SimpleTransmission</type> or the older type
// attribute) with its <mechanicalReduction> (in <actuator>, or directly in
// <transmission> as older files write it): A = diag(N). A chain joint
// without one gets N = 1, another type is not read; both with a warning
// naming the joint. nullopt when no transmission names a chain joint.
// Throws std::invalid_argument "SOURCE:LINE: transmission 'name': ..." for a
// reduction that is not one finite non-zero number, or a joint given twice.
std::optional<Transmission> ReadUrdfTransmissions(const std::string& xml, const std::string& source_name,
                                                  const RobotModel& model, std::vector<std::string>* warnings);

}  // namespace idbench::internal
