#include "idbench/workbench/commands/export_command.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/urdf.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/joints_yaml.h"
#include "idbench/workbench/formats/mjcf_writer.h"
#include "number_format.h"

namespace idbench {

std::string ExportOptions::file_name() const {
  switch (format) {
    case ExportFormat::kMjcf: return "identified.xml";
    case ExportFormat::kUrdf: return "identified.urdf";
    case ExportFormat::kYaml: return "joints.yaml";
  }
  return "";
}

bool ExportOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (identified.empty()) return fail("identified: the identified.json of an identify run is required");
  if (!base_pose.IsValid(why)) return false;
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

std::string ExportReport::BriefReport() const {
  std::string out = "export of robot '" + robot + "' from " + identified + ": " + file_name;
  if (writes) out += " (" + std::to_string(content.size()) + " bytes)";
  out += ", " + std::string(kExportStatusNames.Name(status));
  if (!refused.empty()) out += ": " + refused;
  return out;
}

namespace {

// The transmission identify's actuator-side terms act through: the one
// identified.json records (`transmission.actuator_from_joint`), else (a file
// written before it was recorded) the robot's URDF's.
Eigen::MatrixXd IdentifiedTransmission(const nlohmann::json& json, const RobotModel& model, const std::string& path,
                                       const std::optional<Transmission>& from_urdf) {
  if (!json.contains("transmission")) {
    if (!from_urdf) {
      throw std::invalid_argument(path + ": identified on the actuator side, without `transmission`: the robot's "
                                  "URDF must give the <transmission> it was identified through");
    }
    return from_urdf->actuator_from_joint;
  }
  const nlohmann::json& rows = json.at("transmission").at("actuator_from_joint");
  const int n = model.n_dof();
  if (!rows.is_array() || rows.size() != static_cast<size_t>(n)) {
    throw std::invalid_argument(path + ": transmission.actuator_from_joint: expected " + std::to_string(n) +
                                " rows (robot '" + model.name() + "'), got " + rows.dump().substr(0, 80));
  }
  Transmission recorded;
  recorded.actuator_from_joint.resize(n, n);
  for (int k = 0; k < n; ++k) {
    const std::vector<double> row = rows[static_cast<size_t>(k)].get<std::vector<double>>();
    if (row.size() != static_cast<size_t>(n)) {
      throw std::invalid_argument(path + ": transmission.actuator_from_joint[" + std::to_string(k) + "]: expected " +
                                  std::to_string(n) + " values, got " + std::to_string(row.size()));
    }
    for (int j = 0; j < n; ++j) recorded.actuator_from_joint(k, j) = row[static_cast<size_t>(j)];
  }
  if (std::string why; !recorded.IsValid(n, &why)) throw std::invalid_argument(path + ": transmission." + why);
  return recorded.actuator_from_joint;
}

// The standard parameters are a robot's, within the URDF reader's bounds
// (urdf.h): per link a mass in (0, kMaxLinkMass], a centre of mass within
// kMaxLinkComOffset of the link frame, inertia entries about it within
// kMaxLinkInertia; friction (Fv, Fc) and rotor inertia (Ia) >= 0 and bounded
// as joints.yaml's (joints_yaml.h); every value finite. Throws
// std::invalid_argument naming the entry ("...standard_parameters[20] ('B3.m')").
void CheckStandardParameters(const RobotModel& model, const std::vector<std::string>& names, const Eigen::VectorXd& pi,
                             const std::string& path) {
  auto fail = [&](Eigen::Index k, const std::string& message) {
    throw std::invalid_argument(path + ": physically_consistent.standard_parameters[" + std::to_string(k) + "] ('" +
                                names[static_cast<size_t>(k)] + "'): " + message);
  };
  for (Eigen::Index k = 0; k < pi.size(); ++k) {
    if (!std::isfinite(pi[k])) fail(k, "expected a finite number, got " + Shortest(pi[k]));
  }
  for (int l = 0; l < model.n_links(); ++l) {
    const Eigen::Index o = kInertialParametersPerLink * l;
    const double m = pi[o];
    if (!(m > 0.0 && m <= kMaxLinkMass))
      fail(o, "expected a mass above 0, at most " + Shortest(kMaxLinkMass) + " kg (as a robot file's), got " + Shortest(m));
    const Eigen::Vector3d c = pi.segment<3>(o + 1) / m;
    if (!(c.norm() <= kMaxLinkComOffset)) {
      fail(o + 1, "the centre of mass lies " + Shortest(c.norm()) + " m from the link frame, at most " +
                      Shortest(kMaxLinkComOffset) + " m (as a robot file's)");
    }
    // [Ixx, Ixy, Iyy, Ixz, Iyz, Izz] about the link frame, moved to the centre of mass.
    const auto p = pi.segment<kInertialParametersPerLink>(o);
    Eigen::Matrix3d I_Bcm;
    I_Bcm << p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9];
    I_Bcm -= m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    if (!(I_Bcm.cwiseAbs().maxCoeff() <= kMaxLinkInertia)) {
      fail(o + 4, "an inertia entry about the centre of mass is " + Shortest(I_Bcm.cwiseAbs().maxCoeff()) +
                      " kg m^2, at most " + Shortest(kMaxLinkInertia) + " kg m^2 (as a robot file's)");
    }
  }
  for (Eigen::Index k = kInertialParametersPerLink * model.n_links(); k < pi.size(); ++k) {
    const std::string& name = names[static_cast<size_t>(k)];
    const bool rotor = name.rfind("Ia", 0) == 0;
    const bool nonnegative = rotor || name.rfind("Fv", 0) == 0 || name.rfind("Fc", 0) == 0;
    const double bound = rotor ? kMaxLinkInertia : kMaxJointFriction;
    if ((nonnegative && pi[k] < 0.0) || std::abs(pi[k]) > bound) {
      fail(k, "expected " + std::string(nonnegative ? "0" : "-" + Shortest(bound)) + " to " + Shortest(bound) +
                  (nonnegative ? " (friction and rotor inertia are >= 0)" : "") + ", got " + Shortest(pi[k]));
    }
  }
}

// The robot file's text with an XML comment before each coupled joint's
// <joint name="..."> line (CouplingNote), and `zeros` (the writer's
// attributes holding that joint's 0 friction) taken off that line.
std::string AnnotateCoupledJoints(std::string text, const RobotModel& model, const std::vector<JointDynamicsValues>& joints,
                                  const FrictionModel& friction, const std::vector<std::string>& zeros) {
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].coupled_motors.empty()) continue;
    const std::string name = joints[j].name.empty() ? model.link(static_cast<int>(j)).name + "_joint" : joints[j].name;
    const size_t at = text.find("<joint name=\"" + EscapeXml(name) + "\"");
    if (at == std::string::npos) continue;
    const size_t line = text.rfind('\n', at) + 1;
    const size_t end = text.find('\n', at);
    std::string joint_line = text.substr(line, end - line);
    for (const std::string& zero : zeros) {
      if (const size_t z = joint_line.find(zero); z != std::string::npos) joint_line.erase(z, zero.size());
    }
    // A comment is raw text (no entities); "--" may not appear in it.
    std::string note = CouplingNote(joints[j], friction);
    for (size_t d = note.find("--"); d != std::string::npos; d = note.find("--")) note.replace(d, 2, "- -");
    const std::string indent = text.substr(line, at - line);
    text.replace(line, end - line, indent + "<!-- " + note + " -->\n" + joint_line);
  }
  return text;
}

}  // namespace

std::string FormatIdentifiedModel(ExportFormat format, const RobotModel& model, const FrictionModel& friction,
                                  const Eigen::VectorXd& pi, const std::vector<JointDynamicsValues>& joints) {
  if (format == ExportFormat::kYaml) return FormatJointsYaml(model.name(), joints, friction);
  // A coupled joint has no <dynamics> (its friction is zero in the model): a comment says why.
  const RobotModel identified = ModelWithStandardParameters(model, friction, pi);
  if (format == ExportFormat::kUrdf) return AnnotateCoupledJoints(WriteUrdf(identified), model, joints, friction, {});
  return AnnotateCoupledJoints(WriteMjcf(identified), model, joints, friction,
                               {" armature=\"0\"", " damping=\"0\"", " frictionloss=\"0\""});
}

ExportReport RunExport(const RobotModel& model, const ExportOptions& options,
                       const std::optional<Transmission>& transmission) {
  if (!IsMountedAt(model, options.base_pose)) {
    throw std::invalid_argument("base_pose: the model's gravity is not the world's -z seen from this base; mount the "
                                "model (MountRobot)");
  }
  const std::string& path = options.identified;
  const nlohmann::json json = ParseJsonInput(ReadInputFile(path), path);
  auto field = [&](const nlohmann::json& object, const char* name) -> const nlohmann::json& {
    if (!object.is_object() || !object.contains(name))
      throw std::invalid_argument(path + ": no field '" + name + "': expected the identified.json `identify` writes");
    return object.at(name);
  };
  try {
    // The friction terms identified, on the joint or (joint_side given) the actuator side.
    const std::vector<std::string> terms = field(json, "friction").get<std::vector<std::string>>();
    std::string why;
    std::optional<FrictionModel> friction = ParseFrictionTerms(terms, &why);
    if (!friction) throw std::invalid_argument(path + ": friction: " + why);
    if (json.contains("joint_side")) {
      friction->actuator_from_joint = IdentifiedTransmission(json, model, path, transmission);
    }
    // The physically consistent standard parameters, by name in the robot's order.
    const nlohmann::json& standard = field(field(json, "physically_consistent"), "standard_parameters");
    const std::vector<std::string> names = StandardParameterNames(model, *friction);
    if (!standard.is_array() || standard.size() != names.size()) {
      throw std::invalid_argument(path + ": physically_consistent.standard_parameters: expected " +
                                  std::to_string(names.size()) + " for robot '" + model.name() + "' with friction " +
                                  field(json, "friction").dump() + ", got " + std::to_string(standard.size()) +
                                  ": identified on another robot?");
    }
    Eigen::VectorXd pi(static_cast<Eigen::Index>(names.size()));
    for (size_t k = 0; k < names.size(); ++k) {
      const std::string name = field(standard[k], "name").get<std::string>();
      if (name != names[k]) {
        throw std::invalid_argument(path + ": physically_consistent.standard_parameters[" + std::to_string(k) +
                                    "]: expected '" + names[k] + "' (robot '" + model.name() + "'), got '" + name +
                                    "': identified on another robot?");
      }
      pi[static_cast<Eigen::Index>(k)] = field(standard[k], "value").get<double>();
    }
    CheckStandardParameters(model, names, pi, path);
    // The verdict decides, as for identify.
    const nlohmann::json& verdict = field(json, "verdict");
    ExportReport report;
    report.robot = model.name();
    report.identified = path;
    report.file_name = options.file_name();
    report.fit_to_load = field(verdict, "fit_to_load").get<bool>();
    report.writes = report.fit_to_load || options.write_unverified;
    report.status = report.fit_to_load ? ExportStatus::kWritten
                    : report.writes    ? ExportStatus::kWrittenUnverified
                                       : ExportStatus::kRefused;
    if (!report.fit_to_load) {
      const nlohmann::json& cause = field(verdict, "cause");
      report.refused = "the physically consistent estimate is not a robot model (" +
                       field(verdict, "message").get<std::string>() + ")" +
                       (cause.is_string() ? ": " + cause.get<std::string>() : std::string()) + ". " +
                       options.file_name() +
                       (options.write_unverified ? " is written anyway, as asked (write_unverified)"
                                                 : " is not written (write_unverified writes it anyway)");
    }
    if (!report.writes) return report;
    report.content = FormatIdentifiedModel(options.format, model, *friction, pi,
                                           JointDynamicsFromJson(field(json, "joints"), model, path));
    return report;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": " + e.what() + ": expected the identified.json `identify` writes");
  }
}

}  // namespace idbench
