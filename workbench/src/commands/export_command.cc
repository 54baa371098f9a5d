#include "idbench/workbench/commands/export_command.h"

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
      if (!transmission) {
        throw std::invalid_argument(path + ": identified on the actuator side: the robot's URDF must give the "
                                    "<transmission> it was identified through");
      }
      friction->actuator_from_joint = transmission->actuator_from_joint;
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
    if (options.format == ExportFormat::kYaml) {
      report.content = FormatJointsYaml(model.name(), JointDynamicsFromJson(field(json, "joints")), *friction);
      return report;
    }
    const RobotModel identified = ModelWithStandardParameters(model, *friction, pi);
    report.content = options.format == ExportFormat::kUrdf ? WriteUrdf(identified) : WriteMjcf(identified);
    return report;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": " + e.what() + ": expected the identified.json `identify` writes");
  }
}

}  // namespace idbench
