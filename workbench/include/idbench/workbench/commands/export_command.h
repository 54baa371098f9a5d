// `idbench export`: an identification's robot model again, in a format, from
// what `identify` wrote (identified.json: its friction terms, the physically
// consistent standard parameters and their verdict) and the robot it
// identified: identified.xml (MJCF, formats/mjcf_writer.h), identified.urdf
// or joints.yaml (formats/joints_yaml.h), the same bytes `identify` writes.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/enum_names.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/transmission.h"
#include "idbench/workbench/formats/joints_yaml.h"

namespace idbench {

// What `export` writes (ExportOptions::format): identified.xml, identified.urdf or joints.yaml.
enum class ExportFormat { kMjcf, kUrdf, kYaml };
inline constexpr EnumNames<ExportFormat, 3> kExportFormatNames{"format", {"mjcf", "urdf", "yaml"}};

struct ExportOptions {
  std::string robot = "puma560";  // the robot identified: built-in name or URDF path
  BasePose base_pose;             // as identified: the model given to RunExport must be mounted so
  std::string identified;         // identified.json, as `identify` wrote it (required)
  ExportFormat format = ExportFormat::kMjcf;
  // Write it also when the physically consistent estimate is not fit to load
  // (the verdict in identified.json): the user accepts it.
  bool write_unverified = false;
  std::string out_dir = "out/export";

  // The file written: identified.xml, identified.urdf or joints.yaml.
  std::string file_name() const;
  // Checks the options alone; *why names the bad field.
  bool IsValid(std::string* why) const;
};

// What became of the file (identified.json's verdict and write_unverified).
enum class ExportStatus {
  kWritten,            // fit to load: content is the file
  kWrittenUnverified,  // not fit to load, written as asked (write_unverified): refused says why it is not fit
  kRefused,            // not fit to load: nothing written (refused says why and how to write it anyway)
};
inline constexpr EnumNames<ExportStatus, 3> kExportStatusNames{"status",
                                                               {"written", "written unverified", "refused"}};

struct ExportReport {
  ExportStatus status = ExportStatus::kWritten;
  bool fit_to_load = false;  // identified.json's verdict
  // When not fit to load: the verdict, its cause and whether the file is
  // written (write_unverified); empty otherwise.
  std::string refused;
  bool writes = false;       // fit to load, or write_unverified
  std::string content;       // the file's text (set when writes)
  std::string robot;         // the robot's name
  std::string identified;    // the identified.json read
  std::string file_name;     // the file: identified.xml, identified.urdf or joints.yaml

  // One line: the robot and file, the file's size and the status, with why
  // when not fit to load.
  std::string BriefReport() const;
};

// The identified robot's file in `format` from the physically consistent
// standard parameters pi (StandardParameterNames(model, friction) order) and
// the per-joint values (identified.json's "joints"): what `identify` writes,
// and `export` again from identified.json, one function for both. The URDF
// and MJCF carry a comment (CouplingNote) on each coupled joint and no
// friction or armature for it.
std::string FormatIdentifiedModel(ExportFormat format, const RobotModel& model, const FrictionModel& friction,
                                  const Eigen::VectorXd& pi, const std::vector<JointDynamicsValues>& joints);

// Reads options.identified and rebuilds the identified robot model from
// `model` (loaded and mounted as identified). Terms identified on the
// actuator side act through the transmission identified.json records
// (`transmission`, the one identify used: a log description's or the URDF's);
// `transmission` (the URDF's) only for a file written before it was recorded.
// Throws std::invalid_argument naming identified.json's field for a file that
// is not identify's, that was identified on another robot (its standard
// parameters' names differ), or whose values are not a robot's: not finite,
// beyond the URDF reader's bounds (urdf.h), negative friction or rotor
// inertia, or `joints` not one per joint of the robot (joints_yaml.h).
ExportReport RunExport(const RobotModel& model, const ExportOptions& options,
                       const std::optional<Transmission>& transmission = std::nullopt);

}  // namespace idbench
