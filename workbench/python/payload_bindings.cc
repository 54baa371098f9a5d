// idbench.payload: a payload's mass, centre of mass and inertia, as
// `idbench payload` (payload_command.h), on log files or arrays.
#include "bindings.h"
#include "idbench/workbench/commands/payload_command.h"

namespace idbench::python {

void BindPayload(py::module_& m) {
  const PayloadOptions defaults;
  m.def(
      "payload",
      [](const Robot& robot, const py::object& data, const py::object& unloaded, const std::string& link,
         const std::vector<std::string>& columns, const std::string& angle_unit,
         const std::vector<double>& drive_gains, const std::string& topic, const py::object& base_pose,
         const std::vector<double>& time_window, const std::vector<double>& unloaded_time_window,
         const std::vector<std::string>& friction, double coulomb_smoothing, double coulomb_min_speed, double max_gap,
         double filter_cutoff,
         int filter_order, double max_relative_sigma, double max_projection_distance, bool write_unverified) {
        PayloadOptions options;
        options.robot = robot.source;
        const auto name = [](const py::object& log, const char* arrays) {
          return py::isinstance<py::dict>(log) ? std::string(arrays) : py::str(log).cast<std::string>();
        };
        options.loaded_log = name(data, "<data arrays>");
        options.unloaded_log = unloaded.is_none() ? "" : name(unloaded, "<unloaded arrays>");
        options.payload_link = link;
        options.format.columns = columns;
        options.format.angle_unit = angle_unit;
        options.format.drive_gains = drive_gains;
        options.format.topic = topic;
        options.base_pose = BasePoseArgument(base_pose);
        options.time_window = time_window;
        options.unloaded_time_window = unloaded_time_window;
        options.friction = friction;
        options.coulomb_smoothing = coulomb_smoothing;
        options.coulomb_min_speed = coulomb_min_speed;
        options.max_gap_s = max_gap;
        options.filter.cutoff_hz = filter_cutoff;
        options.filter.order = filter_order;
        options.max_relative_sigma = max_relative_sigma;
        options.max_projection_distance = max_projection_distance;
        options.write_unverified = write_unverified;
        options.out_dir = ".";  // nothing is written: the files are returned
        options.command_line = "python: idbench.payload";
        // Mounted as base_pose says (gravity in its base frame), as identify does.
        const RobotModel model = MountRobot(*robot.model, options.base_pose);
        std::string why;
        if (!options.IsValid(&why) || !options.IsValidFor(model, &why)) throw std::invalid_argument(why);
        PreparedLog loaded = PrepareLogArgument(data, options.loaded_log, model, options.preparation(false));
        std::optional<PreparedLog> unloaded_log;
        if (!unloaded.is_none())
          unloaded_log = PrepareLogArgument(unloaded, options.unloaded_log, model, options.preparation(true));
        PayloadSummary summary;
        {
          py::gil_scoped_release release;
          summary = RunPayloadOnLogs(model, options, std::move(loaded), std::move(unloaded_log));
        }
        py::dict result = py::module_::import("json").attr("loads")(FormatPayloadJson(model, options, summary));
        result["urdf"] = WritesPayloadUrdf(options, summary)
                             ? py::object(py::str(FormatPayloadUrdf(model, options, summary)))
                             : py::object(py::none());
        result["tables"] = FormatPayloadTable(options, summary);
        result["summary"] = summary.BriefReport();
        result["warnings"] = summary.warnings;
        return result;
      },
      py::arg("robot"), py::arg("data"), py::kw_only(), py::arg("unloaded") = py::none(),
      py::arg("link") = std::string(), py::arg("columns") = std::vector<std::string>{},
      py::arg("angle_unit") = defaults.format.angle_unit, py::arg("drive_gains") = std::vector<double>{},
      py::arg("topic") = std::string(), py::arg("base_pose") = py::none(), py::arg("time_window") = std::vector<double>{},
      py::arg("unloaded_time_window") = std::vector<double>{}, py::arg("friction") = defaults.friction,
      py::arg("coulomb_smoothing") = defaults.coulomb_smoothing,
      py::arg("coulomb_min_speed") = defaults.coulomb_min_speed, py::arg("max_gap") = defaults.max_gap_s,
      py::arg("filter_cutoff") = defaults.filter.cutoff_hz, py::arg("filter_order") = defaults.filter.order,
      py::arg("max_relative_sigma") = defaults.max_relative_sigma,
      py::arg("max_projection_distance") = defaults.max_projection_distance, py::arg("write_unverified") = false,
      "The payload on `link` (default: the last) from a log with it (a CSV path or a dict of arrays {t, q, [qd, qdd], "
      "tau | i}) and, optionally, an unloaded log of the same motion. Options as `idbench payload`'s (drive_gains for "
      "motor currents i, base_pose=(x, y, z, roll, pitch, yaw) mounts the robot as identify does). Returns payload.json "
      "as a dict (mass, com, inertia, sigma, verdict, not_identifiable: None where the motion does not determine a "
      "quantity), with urdf (payload.urdf.xml; None unless the verdict is good or write_unverified), tables, summary.");
}

}  // namespace idbench::python
