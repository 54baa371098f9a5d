// The fine re-check of a design against the limits and the clearance
// (FeasibilityCheck, CheckTrajectoryLimits), the DesignInfeasibility it makes,
// and the advice on what to relax (excitation_design.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "design_outcome.h"
#include "excitation_design_internal.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {

using internal::Format;
using internal::kInf;

}  // namespace

bool FeasibilityCheck::feasible() const {
  return std::all_of(margins.begin(), margins.end(), [](const ConstraintMargin& m) { return m.margin >= 0.0; });
}

namespace {

// One violated margin, one line; at_pose: a pose held still (the home pose
// before any search) rather than an instant of a motion.
std::string ExplainMargin(const ConstraintMargin& m, bool at_pose) {
  const std::string when = at_pose ? " at the home pose" : Format(" at t = %.4g s", m.time);
  if (m.quantity == "clearance") {
    return m.pair + Format(" clearance: %.4g m", m.value) + when + Format(" is below its minimum %.4g m", m.limit) +
           (m.held_at_home ? " (its distance at q = 0, closer than the clearance asked)" : "") +
           Format(" by %.3g m\n", -m.margin);
  }
  const char* unit = m.quantity == "qd" ? "rad/s" : m.quantity == "qdd" ? "rad/s²" : m.quantity == "tau" ? "N m" : "rad";
  const bool lower = m.quantity == "q_min";
  const std::string who = m.motor >= 0 ? "motor " + std::to_string(m.motor + 1) + " (joints " + m.driven + ")"
                                       : "joint " + std::to_string(m.joint + 1);
  const std::string what = m.motor >= 0                                     ? (m.quantity == "qd" ? "|θ̇m|" : "|τm|")
                           : m.quantity == "q_min" || m.quantity == "q_max" ? "q"
                                                                            : "|" + m.quantity + "|";
  return who + " " + m.quantity + ": " + what + Format(" = %.6g", m.value) +
         " " + unit + when + " " + (lower ? "is below" : "exceeds") + Format(" the limit %.6g ", m.limit) + unit +
         Format(" by %.3g ", -m.margin) + unit + "\n";
}

std::string ExplainViolations(const FeasibilityCheck& check, bool at_pose) {
  std::string out;
  for (const ConstraintMargin& m : check.margins) {
    if (m.margin < 0.0) out += ExplainMargin(m, at_pose);
  }
  return out;
}

// "obstacles[2], a box 2 × 2 × 0.05 m at (0, 0, -0.026) m" for the scene's
// obstacle i ("" when the scene has none of that index).
std::string DescribeObstacle(const Cell& scene, int i) {
  if (i >= 0 && static_cast<size_t>(i) < scene.obstacles.size()) {
    const Obstacle& o = scene.obstacles[static_cast<size_t>(i)];
    const Eigen::Vector3d& s = o.shape.size;
    const Eigen::Vector3d p = o.X_WO.translation();
    const std::string shape = o.shape.kind == Shape::Kind::kBox        ? Format("a box %g", s.x()) + Format(" × %g", s.y()) + Format(" × %g m", s.z())
                              : o.shape.kind == Shape::Kind::kCylinder ? Format("a cylinder of radius %g m", s.x()) + Format(", %g m long", s.z())
                              : o.shape.kind == Shape::Kind::kSphere   ? Format("a sphere of radius %g m", s.x())
                                                                       : std::string("a mesh");
    return "obstacles[" + std::to_string(i) + "], " + shape + Format(" at (%g", p.x()) + Format(", %g", p.y()) +
           Format(", %g) m", p.z());
  }
  return "";
}

}  // namespace

std::string FeasibilityCheck::Explain() const { return ExplainViolations(*this, false); }

const ConstraintMargin* FeasibilityCheck::ClosestObstacle() const {
  const ConstraintMargin* closest = nullptr;
  for (const ConstraintMargin& m : margins) {
    const bool cell = m.other == ClearanceOther::kFloor || m.other == ClearanceOther::kObstacle;
    if (m.quantity == "clearance" && cell && (!closest || m.value < closest->value)) closest = &m;
  }
  return closest;
}

std::string FeasibilityCheck::ClosestObstacleLine() const {
  const ConstraintMargin* m = ClosestObstacle();
  if (!m) return "";
  return "closest obstacle: " + m->obstacle + Format(", %.4g m from ", m->value) + m->link +
         Format(" at t = %.4g s (minimum %.4g m)", m->time, m->limit);
}

FeasibilityCheck CheckTrajectoryLimits(const RobotModel& model, const std::vector<JointLimits>& limits,
                                       const Trajectory& trajectory, double rate_hz, const ClearanceModel* clearance,
                                       const ActuatorLimits& actuators) {
  const int n = model.n_dof();
  FeasibilityCheck check;
  check.rate_hz = rate_hz;
  const char* names[5] = {"q_min", "q_max", "qd", "qdd", "tau"};
  auto limit_of = [&](int j, int i) {
    const JointLimits& l = limits[static_cast<size_t>(j)];
    const double values[5] = {l.q_min, l.q_max, l.qd_max, l.qdd_max, l.tau_max};
    return values[i];
  };
  std::vector<ConstraintMargin> worst;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < 5; ++i) {
      ConstraintMargin m;
      m.quantity = names[i];
      m.joint = j;
      m.limit = limit_of(j, i);
      m.margin = kInf;
      worst.push_back(m);
    }
  }
  const size_t n_pairs = clearance ? clearance->pairs().size() : 0;
  for (size_t i = 0; i < n_pairs; ++i) {
    ConstraintMargin m;
    m.quantity = "clearance";
    m.joint = static_cast<int>(i);
    m.pair = clearance->pairs()[i].Name(model);
    m.limit = clearance->pairs()[i].minimum;
    m.held_at_home = m.limit < clearance->min_clearance();
    const ClearancePair& pair = clearance->pairs()[i];
    m.other = pair.other();
    if (m.other != ClearanceOther::kLink) m.obstacle = pair.Other(model);
    m.obstacle_index = pair.obstacle;
    m.link = model.link(pair.link_a).name;
    m.value = kInf;  // the closest distance so far
    m.margin = kInf;
    worst.push_back(m);
  }
  // Per motor its velocity and torque (after the joints' and the pairs').
  const size_t first_motor = worst.size();
  const int n_motors = static_cast<int>(actuators.motors.size());
  for (int k = 0; k < n_motors; ++k) {
    for (int i = 0; i < 2; ++i) {
      ConstraintMargin m;
      m.quantity = i == 0 ? "qd" : "tau";
      m.motor = m.joint = k;
      m.driven = actuators.DrivenJoints(model, k);
      const ActuatorLimit& l = actuators.motors[static_cast<size_t>(k)];
      m.limit = i == 0 ? l.qd_max : l.tau_max;
      m.margin = kInf;
      worst.push_back(m);
    }
  }
  const Eigen::MatrixXd motor_torque_from_joint =
      n_motors > 0 ? actuators.MotorTorqueFromJoint() : Eigen::MatrixXd();
  // Per pair, the last instant GJK measured (its joint angles and distance,
  // or the capsules' lower bound when pruned): a later instant is skipped
  // while that distance, less how far the joints have moved the two sides
  // since (ClearancePair::reach), stays above the pair's least distance so
  // far. At 1 kHz the joints move little between instants, so GJK runs
  // mostly where a pair nears a new minimum; the minima are unchanged.
  constexpr double kGjkTolerance = 1e-7;  // [m]
  Eigen::MatrixXd anchor_q(n, static_cast<Eigen::Index>(n_pairs));
  std::vector<double> anchor_distance(n_pairs, -kInf);
  RobotData data(model);
  JointState x(n);
  const long steps = static_cast<long>(std::floor(trajectory.duration() * rate_hz + 1e-9));
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    trajectory.Evaluate(t, &x);
    Eigen::VectorXd tau = InverseDynamics(model, x.q, x.qd, x.qdd, &data);
    AddJointDynamicsTorque(model, x.qd, x.qdd, &tau);
    for (int j = 0; j < n; ++j) {
      const double values[5] = {x.q[j], x.q[j], std::abs(x.qd[j]), std::abs(x.qdd[j]), std::abs(tau[j])};
      for (int i = 0; i < 5; ++i) {
        ConstraintMargin& w = worst[static_cast<size_t>(5 * j + i)];
        const double margin = i == 0 ? values[i] - w.limit : w.limit - values[i];
        if (margin < w.margin) w.margin = margin, w.time = t, w.value = values[i];
      }
    }
    if (n_motors > 0) {
      const Eigen::VectorXd thetad_m = actuators.transmission.actuator_from_joint * x.qd;
      const Eigen::VectorXd tau_m = motor_torque_from_joint * tau;
      for (int k = 0; k < n_motors; ++k) {
        const double values[2] = {std::abs(thetad_m[k]), std::abs(tau_m[k])};
        for (int i = 0; i < 2; ++i) {
          ConstraintMargin& w = worst[first_motor + static_cast<size_t>(2 * k + i)];
          const double margin = w.limit - values[i];
          if (margin < w.margin) w.margin = margin, w.time = t, w.value = values[i];
        }
      }
    }
    for (size_t i = 0; i < n_pairs; ++i) {
      ConstraintMargin& w = worst[static_cast<size_t>(5 * n) + i];
      const Eigen::Index a = static_cast<Eigen::Index>(i);
      double moved_bound = anchor_distance[i] - kGjkTolerance;
      const std::vector<double>& reach = clearance->pairs()[i].reach;
      for (int j = 0; j < n && moved_bound > w.value; ++j) {
        moved_bound -= reach[static_cast<size_t>(j)] * std::abs(x.q[j] - anchor_q(j, a));
      }
      if (moved_bound > w.value) continue;
      // data holds the poses InverseDynamics computed.
      const double distance = clearance->ComputePair(data, static_cast<int>(i), w.value).distance;
      anchor_distance[i] = distance;
      anchor_q.col(a) = x.q;
      const double margin = distance - w.limit;
      if (margin < w.margin) w.margin = margin, w.time = t, w.value = distance;
    }
  }
  for (const ConstraintMargin& m : worst) {
    if (std::isfinite(m.limit)) check.margins.push_back(m);
  }
  return check;
}

namespace internal {

DesignInfeasibility ExplainInfeasibility(const std::string& summary, FeasibilityCheck check,
                                         std::vector<std::string> advice, bool before_search) {
  DesignInfeasibility out;
  out.explanation = summary + "\n" + ExplainViolations(check, before_search);
  if (!advice.empty()) out.explanation += "to relax:\n";
  for (const std::string& a : advice) out.explanation += "  " + a + "\n";
  if (!out.explanation.empty() && out.explanation.back() == '\n') out.explanation.pop_back();
  out.check = std::move(check);
  out.advice = std::move(advice);
  out.before_search = before_search;
  return out;
}

DesignStatus InfeasibilityStatus(const DesignInfeasibility& infeasibility) {
  if (!infeasibility.before_search) return DesignStatus::kInfeasible;
  for (const ConstraintMargin& m : infeasibility.check.margins) {
    if (m.margin < 0.0 && m.other == ClearanceOther::kObstacle) return DesignStatus::kNoRoom;
  }
  return DesignStatus::kNoMotionPossible;
}

}  // namespace internal

std::vector<std::string> RelaxationAdvice(const FeasibilityCheck& check, const DesignOptions& options,
                                          bool before_search) {
  std::vector<std::string> advice;
  auto add = [&](const std::string& line) {
    if (std::find(advice.begin(), advice.end(), line) == advice.end()) advice.push_back(line);
  };
  const double ramp = options.ramp_seconds, motion_end = ramp + options.period_duration();
  bool in_motion = false;  // a violation outside the ramps
  std::vector<int> obstacles;            // the scene's obstacles too close (indices), in order
  std::map<int, std::string> too_close;  // obstacle -> "link (distance m), ..."
  std::map<int, double> limit;           // obstacle -> the clearance asked [m]
  for (const ConstraintMargin& m : check.margins) {
    if (m.margin >= 0.0) continue;
    const std::string joint = "joint " + std::to_string(m.joint + 1);
    const std::string motor = "actuators[" + std::to_string(m.motor) + "]";
    if (!before_search && ramp > 0.0 && (m.time < ramp || m.time > motion_end)) {
      add(Format("ramp_seconds (now %g s): longer ramps from and to the home pose (violated during t < %g s", ramp, ramp) +
          Format(" or t > %g s)", motion_end));
      continue;
    }
    in_motion = true;
    if (m.quantity == "clearance" && m.other == ClearanceOther::kFloor) {
      add(Format("`clearance` (now %g m), a `home` pose or a base_pose with ", options.clearance) + m.link +
          " further from the floor, or \"floor\": false in the scene");
    } else if (m.quantity == "clearance" && m.other == ClearanceOther::kObstacle) {
      // Per obstacle: every link that comes too close to it, on one line (below).
      auto& links = too_close[m.obstacle_index];
      if (links.empty()) obstacles.push_back(m.obstacle_index);
      links += (links.empty() ? "" : ", ") + m.link + Format(" (%.3g m)", m.value);
      limit[m.obstacle_index] = m.limit;
    } else if (m.quantity == "clearance" && m.other == ClearanceOther::kGroundLink) {
      add(Format("`clearance` (now %g m), or a `home` pose with ", options.clearance) + m.link +
          " further from the robot file's fixed link '" + m.obstacle + "' (the ground it stands on)");
    } else if (m.quantity == "clearance") {
      add(Format("`clearance` (now %g m), or a `home` pose with the links further apart", options.clearance));
    } else if (m.motor >= 0 && m.quantity == "tau") {
      add("motor " + std::to_string(m.motor + 1) + "'s torque limit " + motor +
          ".tau_max in the `limits` file, or a `home` where gravity loads it less");
    } else if (m.motor >= 0) {
      add("motor " + std::to_string(m.motor + 1) + "'s velocity limit " + motor +
          ".qd_max in the `limits` file, or fewer `harmonics`, a lower `f0` or a longer `duration`");
    } else if (m.quantity == "q_min" || m.quantity == "q_max") {
      add(joint + "'s range q_min..q_max in the `limits` file" + (before_search ? ", or a `home` inside it" : ""));
    } else if (m.quantity == "tau") {
      add(joint + "'s torque limit tau_max in the `limits` file, or a `home` where gravity loads it less");
    } else {
      add(joint + "'s " + (m.quantity == "qd" ? "velocity limit qd_max" : "acceleration limit qdd_max") +
          " in the `limits` file, or fewer `harmonics`, a lower `f0` or a longer `duration`");
    }
  }
  for (const int i : obstacles) {
    const std::string what = DescribeObstacle(options.scene, i);
    const std::string name = i >= 0 && static_cast<size_t>(i) < options.scene.obstacles.size()
                                 ? options.scene.ObstacleName(i)
                                 : "obstacle " + std::to_string(i);
    add("the scene's obstacle '" + name + "'" + (what.empty() ? "" : " (" + what + ")") + ": " + too_close[i] +
        Format(" closer than the %.3g m asked", limit[i]) + (before_search ? " at the home pose" : "") +
        ": move or remove it, or a base_pose further from it");
  }
  if (!before_search && (in_motion || advice.empty())) {
    add(Format("`margin` (now %g), which tightens every limit during the search", options.margin));
  }
  return advice;
}

}  // namespace idbench
