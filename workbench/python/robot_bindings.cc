// idbench.Robot: a robot model (built-in or from a URDF file), immutable.
#include <stdexcept>

#include "bindings.h"

namespace idbench::python {
namespace {

Robot LoadRobotForPython(const std::string& name_or_path, const std::map<std::string, double>& lock,
                         const std::string& tip) {
  UrdfLoadOptions load;
  load.locked_joints = lock;
  load.tip_link = tip;
  std::string why;
  if (!load.IsValid(&why)) throw std::invalid_argument(why);
  UrdfLoadResult loaded = LoadRobot(name_or_path, load);
  return Robot{std::make_shared<const RobotModel>(std::move(loaded.model)), name_or_path, std::move(loaded.warnings),
               std::move(loaded.transmission)};
}

}  // namespace

BasePose BasePoseArgument(const py::object& value) {
  BasePose pose;
  if (value.is_none()) return pose;
  // A wrong type is a TypeError naming the keyword (pybind11's cast_error
  // would be a RuntimeError naming C++ types).
  const auto wrong_type = [&] {
    return py::type_error("base_pose: expected a sequence of 6 numbers (x, y, z, roll, pitch, yaw) [m, rad], got " +
                          std::string(py::str(py::type::of(value).attr("__name__"))));
  };
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value)) throw wrong_type();
  std::vector<double> xyz_rpy;
  try {
    xyz_rpy = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw wrong_type();
  }
  if (xyz_rpy.size() != 6) {
    throw std::invalid_argument("base_pose: expected (x, y, z, roll, pitch, yaw), got " + std::to_string(xyz_rpy.size()) +
                                " values");
  }
  std::copy(xyz_rpy.begin(), xyz_rpy.end(), pose.xyz_rpy.begin());
  std::string why;
  if (!pose.IsValid(&why)) throw std::invalid_argument(why);
  return pose;
}

void BindRobot(py::module_& m) {
  py::class_<Robot>(m, "Robot", "A robot model (built-in or from a URDF file); immutable")
      .def(py::init(&LoadRobotForPython), py::arg("robot"), py::arg("lock") = std::map<std::string, double>{},
           py::arg("tip") = std::string(),
           "Loads a built-in robot ('paper6r', 'puma560') or a URDF file. lock: {joint: value} held fixed "
           "(--lock); tip: the arm's last link (--tip).")
      .def_property_readonly("name", [](const Robot& r) { return r.model->name(); })
      .def_property_readonly("n_dof", [](const Robot& r) { return r.model->n_dof(); })
      .def_property_readonly("joint_names", [](const Robot& r) {
        std::vector<std::string> names;
        for (const Link& link : r.model->links()) names.push_back(link.joint_name);
        return names;
      })
      .def_property_readonly("link_names", [](const Robot& r) {
        std::vector<std::string> names;
        for (const Link& link : r.model->links()) names.push_back(link.name);
        return names;
      })
      .def_readonly("warnings", &Robot::warnings)
      .def("__repr__", [](const Robot& r) {
        return "<idbench.Robot '" + r.model->name() + "', " + std::to_string(r.model->n_dof()) + " joints>";
      });
}

}  // namespace idbench::python
