// The home pose an excitation design's motion is built around: every start
// oscillates about it, so it must be clear of the limits with room to move.
//
// A pose is checked held still (qd = qdd = 0) against the joint ranges, the
// torque limits (gravity), the motors' torque limits (τm = A⁻ᵀ·τ, when the
// design has actuator limits) and the clearance (CheckPose). It is a home with
// room when, besides, each joint is at least 10 % of its range inside it, the
// gravity torque at most 1 − margin of its limit (a joint's or a motor's),
// and every clearance pair at least 10 cm beyond the minimum clearance (less
// where the joints cannot give a pair that much, ClearanceRoomAsked): a first
// dip of a joint then does not reach the floor or another link.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/link_clearance.h"
#include "idbench/engine/robot_model.h"
#include "idbench/excitation/actuator_limits.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {

// How far inside each joint's range a home stays, as a fraction of the range.
inline constexpr double kHomeRangeRoom = 0.1;

// The limits (the joints', and the motors' of `actuators`) and the clearance
// of the pose q [rad] (n_dof) held still; its margins have time 0.
FeasibilityCheck CheckPose(const RobotModel& model, const std::vector<JointLimits>& limits, const Eigen::VectorXd& q,
                           const ClearanceModel* clearance, const ActuatorLimits& actuators = {});

// The room a home asks of each clearance pair (one entry per pair of
// clearance; none without it) [m]: 0.1 m, but at most half of what the joints
// can give the pair — the most its distance exceeds the minimum clearance at
// q or with any one joint moved ±0.5 rad from q — and none for a pair whose
// distance such moves change by less than 5 mm (a base link turning on the
// floor, wrist links a few cm apart by construction, an upper arm whose
// shoulder end stays 0.11 m above the floor).
std::vector<double> ClearanceRoomAsked(const RobotModel& model, const std::vector<JointLimits>& limits,
                                       const Eigen::VectorXd& q, const ClearanceModel* clearance);

// How much room q has, in units of each constraint's scale: the smallest of
//   (distance to the nearer range end)/range − 0.1,
//   1 − margin − |τ_gravity|/τ_max, and per motor of `actuators`
//   1 − margin − |τm|/τm_max with τm = A⁻ᵀ·τ_gravity,
//   (clearance − minimum − asked)/0.1 m, asked = room_asked[pair] (0.1 m
//   when not given, see ClearanceRoomAsked);
// ≥ 0 for a home with room.
double HomeRoom(const RobotModel& model, const std::vector<JointLimits>& limits, double margin,
                const Eigen::VectorXd& q, const ClearanceModel* clearance,
                const std::vector<double>* room_asked = nullptr, const ActuatorLimits& actuators = {});

struct HomePose {
  Eigen::VectorXd q;         // [rad] (n_dof)
  std::string source;        // "mid-range", "searched" (from the mid-range), "given"
  double room = 0.0;         // HomeRoom at q (≥ 0 when found)
  bool found = false;        // false: no pose with room; q is the best tried
};

// The middle of the joint ranges when it has room (each pair asked the room
// ClearanceRoomAsked gives there); otherwise a pose with room near it, found by a deterministic pattern search from it that maximises
// HomeRoom (per joint a step either way, 0.5 rad or a quarter of the range at
// first, halved down to 1 mrad; each joint kept 10 % inside its range).
HomePose FindHomePose(const RobotModel& model, const std::vector<JointLimits>& limits, double margin,
                      const ClearanceModel* clearance, const ActuatorLimits& actuators = {});

}  // namespace idbench
