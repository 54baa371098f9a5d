// joints.yaml: per joint, what a controller loads next to the identified
// URDF (the physically consistent estimate's friction, offset and rotor
// inertia, the drive gain the log was read with), and the same values as
// identified.json's "joints" holds them, so that `export` writes the bytes
// `identify` wrote from that file alone.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

// One joint's values; nullopt: not in the model, or a coupled joint's.
struct JointDynamicsValues {
  std::string name;
  std::optional<double> viscous, coulomb, offset, rotor_inertia, drive_gain;
  std::vector<int> coupled_motors;  // 0-based motors k with A(k, j) ≠ 0 when the joint is coupled; else empty
};

// Why a coupled joint carries no friction or rotor inertia, and where the
// actuator-side values are (the terms `friction` holds).
std::string CouplingNote(const JointDynamicsValues& v, const FrictionModel& friction);

// identified.json's "joints": [{name, viscous, coulomb, offset, rotor_inertia,
// drive_gain, [coupled_motors (1-based)]}], null for a missing value.
nlohmann::json JointDynamicsJson(const std::vector<JointDynamicsValues>& joints);
// Beyond any robot joint: the largest viscous [N m s/rad], Coulomb and offset
// [N m] friction a joint's values may hold. Rotor inertia is bounded as a
// link's inertia entry (kMaxLinkInertia, urdf.h), drive gains as
// JointLogFormat's.
inline constexpr double kMaxJointFriction = 1e6;

// The values back from that array, checked against `model`: one per joint,
// named as its joints in order; each value null or finite, viscous, coulomb
// and rotor_inertia >= 0, within the bounds above; coupled_motors 1..n_dof.
// Throws std::invalid_argument "SOURCE: joints[2].viscous: ..." naming the
// field and the value, nlohmann::json::exception for another shape.
std::vector<JointDynamicsValues> JointDynamicsFromJson(const nlohmann::json& joints, const RobotModel& model,
                                                       const std::string& source);

// joints.yaml for robot `robot_name`.
std::string FormatJointsYaml(const std::string& robot_name, const std::vector<JointDynamicsValues>& joints,
                             const FrictionModel& friction);

}  // namespace idbench
