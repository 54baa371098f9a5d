#include "idbench/workbench/formats/joints_yaml.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "idbench/engine/urdf.h"
#include "idbench/logs/joint_log_format.h"
#include "number_format.h"

namespace idbench {
namespace {

// "motors 5 and 6" (1-based) for a coupled joint's comment.
std::string MotorList(const std::vector<int>& motors) {
  std::string out = motors.size() == 1 ? "motor " : "motors ";
  for (size_t i = 0; i < motors.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == motors.size() ? " and " : ", ") + std::to_string(motors[i] + 1);
  }
  return out;
}

}  // namespace

std::string CouplingNote(const JointDynamicsValues& v, const FrictionModel& friction) {
  std::string terms;
  for (int k : v.coupled_motors) {
    const std::string m = "m" + std::to_string(k + 1);
    for (const auto& [on, term] : {std::pair{friction.viscous, "Fv"}, {friction.coulomb, "Fc"},
                                   {friction.offset, "offset"}, {friction.rotor_inertia, "Ia"}}) {
      if (on) terms += (terms.empty() ? "" : ", ") + std::string(term) + m;
    }
  }
  return "joint '" + v.name + "' is coupled: " + MotorList(v.coupled_motors) +
         (v.coupled_motors.size() == 1 ? " turns" : " turn") + " with it (transmission actuator_from_joint), so its friction and rotor inertia are per motor, "
         "not per joint; not 0 but not expressible here: see identified.json's standard_parameters " +
         (terms.empty() ? std::string("(none in the model)") : terms);
}

nlohmann::json JointDynamicsJson(const std::vector<JointDynamicsValues>& values) {
  auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json joints = nlohmann::json::array();
  for (const JointDynamicsValues& v : values) {
    nlohmann::json joint = {{"name", v.name}, {"viscous", value(v.viscous)}, {"coulomb", value(v.coulomb)},
                            {"offset", value(v.offset)}, {"rotor_inertia", value(v.rotor_inertia)},
                            {"drive_gain", value(v.drive_gain)}};
    if (!v.coupled_motors.empty()) {
      nlohmann::json motors = nlohmann::json::array();
      for (int k : v.coupled_motors) motors.push_back(k + 1);
      joint["coupled_motors"] = motors;
    }
    joints.push_back(joint);
  }
  return joints;
}

std::vector<JointDynamicsValues> JointDynamicsFromJson(const nlohmann::json& joints, const RobotModel& model,
                                                       const std::string& source) {
  auto fail = [&](const std::string& field, const std::string& message) {
    throw std::invalid_argument(source + ": " + field + ": " + message);
  };
  if (!joints.is_array() || joints.size() != static_cast<size_t>(model.n_dof())) {
    fail("joints", "expected one entry per joint of robot '" + model.name() + "' (" + std::to_string(model.n_dof()) +
                       "), got " + (joints.is_array() ? std::to_string(joints.size()) : std::string(joints.type_name())) +
                       ": identified on another robot?");
  }
  // A value: null, or finite within [lowest, highest].
  auto value = [&](const nlohmann::json& joint, const std::string& where, const char* name, double lowest,
                   double highest, const char* unit) -> std::optional<double> {
    const nlohmann::json& v = joint.at(name);
    if (v.is_null()) return std::nullopt;
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lowest || x > highest) {
      fail(where + "." + name, "expected " + (lowest < 0.0 ? "-" + Shortest(highest) : Shortest(lowest)) + " to " +
                                   Shortest(highest) + " " + unit + (lowest == 0.0 ? " (friction and rotor inertia are >= 0)" : "") +
                                   ", got " + Shortest(x));
    }
    return x;
  };
  std::vector<JointDynamicsValues> out;
  for (size_t j = 0; j < joints.size(); ++j) {
    const nlohmann::json& joint = joints[j];
    const std::string where = "joints[" + std::to_string(j) + "]";
    JointDynamicsValues& v = out.emplace_back();
    v.name = joint.at("name").get<std::string>();
    const std::string& expected = model.link(static_cast<int>(j)).joint_name;
    if (v.name != expected) {
      fail(where + ".name", "expected '" + expected + "' (robot '" + model.name() + "'), got '" + v.name +
                                "': identified on another robot?");
    }
    v.viscous = value(joint, where, "viscous", 0.0, kMaxJointFriction, "N m s/rad");
    v.coulomb = value(joint, where, "coulomb", 0.0, kMaxJointFriction, "N m");
    v.offset = value(joint, where, "offset", -kMaxJointFriction, kMaxJointFriction, "N m");
    v.rotor_inertia = value(joint, where, "rotor_inertia", 0.0, kMaxLinkInertia, "kg m^2");
    v.drive_gain = value(joint, where, "drive_gain", -JointLogFormat::kMaxDriveGain, JointLogFormat::kMaxDriveGain, "N m/A");
    if (v.drive_gain && std::abs(*v.drive_gain) < JointLogFormat::kMinDriveGain) {
      fail(where + ".drive_gain", "expected a gain of magnitude " + Shortest(JointLogFormat::kMinDriveGain) + " to " +
                                      Shortest(JointLogFormat::kMaxDriveGain) + " N m/A, got " + Shortest(*v.drive_gain));
    }
    if (joint.contains("coupled_motors")) {
      for (int k : joint.at("coupled_motors").get<std::vector<int>>()) {
        if (k < 1 || k > model.n_dof()) {
          fail(where + ".coupled_motors", "expected motors 1 to " + std::to_string(model.n_dof()) + ", got " +
                                              std::to_string(k));
        }
        v.coupled_motors.push_back(k - 1);
      }
    }
  }
  return out;
}

std::string FormatJointsYaml(const std::string& robot_name, const std::vector<JointDynamicsValues>& joints,
                             const FrictionModel& friction) {
  auto value = [](const std::optional<double>& v) { return v ? Shortest(*v) : std::string("null"); };
  std::string out = "# idbench identify: per-joint friction and drive values of the physically consistent estimate\n"
                    "# (the rigid-body parameters are in identified.urdf). Units: viscous [N m s/rad], coulomb and\n"
                    "# offset [N m], rotor_inertia [kg m^2], drive_gain [N m/A]; null: not in the model, or a coupled\n"
                    "# joint's (see its comment), never a measured zero.\n"
                    "robot: \"" + robot_name + "\"\njoints:\n";
  for (const JointDynamicsValues& v : joints) {
    out += "  - name: \"" + v.name + "\"\n";
    if (!v.coupled_motors.empty()) out += "    # " + CouplingNote(v, friction) + "\n";
    out += "    viscous: " + value(v.viscous) + "\n    coulomb: " + value(v.coulomb) +
           "\n    offset: " + value(v.offset) + "\n    rotor_inertia: " + value(v.rotor_inertia) +
           "\n    drive_gain: " + value(v.drive_gain) + "\n";
  }
  return out;
}

}  // namespace idbench
