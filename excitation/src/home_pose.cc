#include "idbench/excitation/home_pose.h"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <limits>

#include "idbench/excitation/constant_acceleration.h"

namespace idbench {
namespace {

constexpr double kRangeRoom = kHomeRangeRoom;
constexpr double kClearanceRoom = 0.1;  // [m] beyond the minimum clearance
constexpr double kClearanceScale = 0.1; // [m]

bool FiniteRange(const JointLimits& l) { return std::isfinite(l.q_min) && std::isfinite(l.q_max); }

}  // namespace

FeasibilityCheck CheckPose(const RobotModel& model, const std::vector<JointLimits>& limits, const Eigen::VectorXd& q,
                           const ClearanceModel* clearance, const ActuatorLimits& actuators) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
  // Held still for an instant: one sample at t = 0.
  const ConstantAccelerationTrajectory still(q, zero, zero, 1e-6);
  return CheckTrajectoryLimits(model, limits, still, 1.0, clearance, actuators);
}

std::vector<double> ClearanceRoomAsked(const RobotModel& model, const std::vector<JointLimits>& limits,
                                       const Eigen::VectorXd& q, const ClearanceModel* clearance) {
  constexpr double kStep = 0.5;          // [rad]
  constexpr double kUnchanged = 0.005;   // [m]
  if (!clearance) return {};
  // The distance of every pair (margins in pair order, after the joints').
  auto distances = [&](const Eigen::VectorXd& pose) {
    std::vector<double> d;
    for (const ConstraintMargin& m : CheckPose(model, limits, pose, clearance).margins) {
      if (m.quantity == "clearance") d.push_back(m.value);
    }
    return d;
  };
  const std::vector<double> at_q = distances(q);
  std::vector<double> change(at_q.size(), 0.0), most = at_q;
  for (int j = 0; j < model.n_dof(); ++j) {
    for (double sign : {1.0, -1.0}) {
      Eigen::VectorXd moved = q;
      moved[j] += sign * kStep;
      const std::vector<double> d = distances(moved);
      for (size_t i = 0; i < d.size(); ++i) {
        change[i] = std::max(change[i], std::abs(d[i] - at_q[i]));
        most[i] = std::max(most[i], d[i]);
      }
    }
  }
  std::vector<double> asked(change.size(), 0.0);
  for (size_t i = 0; i < change.size(); ++i) {
    if (change[i] >= kUnchanged) {
      asked[i] = std::clamp(0.5 * (most[i] - clearance->pairs()[i].minimum), 0.0, kClearanceRoom);
    }
  }
  return asked;
}

double HomeRoom(const RobotModel& model, const std::vector<JointLimits>& limits, double margin,
                const Eigen::VectorXd& q, const ClearanceModel* clearance, const std::vector<double>* room_asked,
                const ActuatorLimits& actuators) {
  const FeasibilityCheck check = CheckPose(model, limits, q, clearance, actuators);
  double room = std::numeric_limits<double>::infinity();
  for (const ConstraintMargin& m : check.margins) {
    if (m.quantity == "clearance") {
      const size_t pair = static_cast<size_t>(m.joint);
      const double asked = room_asked && pair < room_asked->size() ? (*room_asked)[pair] : kClearanceRoom;
      room = std::min(room, (m.margin - asked) / kClearanceScale);
    } else if (m.quantity == "tau") {  // a joint's, or a motor's (τm = A⁻ᵀ·τ)
      room = std::min(room, m.margin / m.limit - margin);
    } else if (m.quantity == "q_min" || m.quantity == "q_max") {
      const JointLimits& l = limits[static_cast<size_t>(m.joint)];
      if (FiniteRange(l)) room = std::min(room, m.margin / (l.q_max - l.q_min) - kRangeRoom);
    }
  }
  return room;
}

HomePose FindHomePose(const RobotModel& model, const std::vector<JointLimits>& limits, double margin,
                      const ClearanceModel* clearance, const ActuatorLimits& actuators) {
  const int n = model.n_dof();
  Eigen::VectorXd middle = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd first_step = Eigen::VectorXd::Constant(n, 0.5);  // [rad]
  for (int j = 0; j < n; ++j) {
    const JointLimits& l = limits[static_cast<size_t>(j)];
    if (!FiniteRange(l)) continue;
    middle[j] = 0.5 * (l.q_min + l.q_max);
    first_step[j] = std::min(0.5, 0.25 * (l.q_max - l.q_min));
  }
  // Pattern search from `start`: per joint, a step either way while it adds
  // room; the steps halve when none does. The first pose with room ends it.
  auto search = [&](const Eigen::VectorXd& start, const std::string& source) {
    HomePose home;
    home.q = start;
    home.source = source;
    Eigen::VectorXd step = first_step;
    const std::vector<double> asked = ClearanceRoomAsked(model, limits, home.q, clearance);
    home.room = HomeRoom(model, limits, margin, home.q, clearance, &asked, actuators);
    constexpr double kSmallestStep = 1e-3;  // [rad]
    while (home.room < 0.0 && step.maxCoeff() >= kSmallestStep) {
      bool moved = false;
      for (int j = 0; j < n && home.room < 0.0; ++j) {
        for (double sign : {1.0, -1.0}) {
          Eigen::VectorXd q = home.q;
          q[j] += sign * step[j];
          const JointLimits& l = limits[static_cast<size_t>(j)];
          if (FiniteRange(l)) {
            const double inset = kRangeRoom * (l.q_max - l.q_min);
            q[j] = std::clamp(q[j], l.q_min + inset, l.q_max - inset);
          }
          const double room = HomeRoom(model, limits, margin, q, clearance, &asked, actuators);
          if (room > home.room) {
            home.q = q, home.room = room, home.source = "searched", moved = true;
            break;
          }
        }
      }
      if (!moved) step *= 0.5;
    }
    home.found = home.room >= 0.0;
    return home;
  };
  HomePose home = search(middle, "mid-range");
  // An obstacle on one side (a wall) can trap the search: again with the
  // first joint turned a quarter, half and three quarters round, where its
  // range allows; the first with room, else the one with most room.
  const JointLimits& l0 = limits[0];
  for (double turn : {0.5, -0.5, 1.0, -1.0}) {
    if (home.found) break;
    Eigen::VectorXd start = middle;
    start[0] += turn * std::numbers::pi;
    if (FiniteRange(l0)) {
      const double inset = kRangeRoom * (l0.q_max - l0.q_min);
      if (start[0] < l0.q_min + inset || start[0] > l0.q_max - inset) continue;
    }
    HomePose turned = search(start, "searched");
    if (turned.room > home.room) home = turned;
  }
  return home;
}

}  // namespace idbench
