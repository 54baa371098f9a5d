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
// The values back from that array; throws nlohmann::json::exception for
// another shape.
std::vector<JointDynamicsValues> JointDynamicsFromJson(const nlohmann::json& joints);

// joints.yaml for robot `robot_name`.
std::string FormatJointsYaml(const std::string& robot_name, const std::vector<JointDynamicsValues>& joints,
                             const FrictionModel& friction);

}  // namespace idbench
