// The Python module `idbench` (pybind11), one file per part: robot_bindings.cc
// (Robot), log_bindings.cc (joint logs in and out: simulate), identify_bindings.cc
// (base parameters, regressor, identify), payload_bindings.cc, design_bindings.cc, render_bindings.cc;
// idbench_module.cc calls each Bind in turn. What several parts share is here.
#pragma once

// Every part sees the same type casters (pybind11: include them in every
// translation unit that converts these types, or the conversions differ).
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <map>
#include <stdexcept>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/enum_names.h"
#include "idbench/engine/robot_library.h"
#include "idbench/engine/transmission.h"
#include "idbench/logs/joint_log_pipeline.h"

namespace idbench::python {

namespace py = pybind11;

// A robot loaded once and shared, immutable, by every call that takes it.
struct Robot {
  std::shared_ptr<const RobotModel> model;
  std::string source;                 // name or path as given
  std::vector<std::string> warnings;  // from loading the file
  std::optional<Transmission> transmission;  // the URDF's <transmission> elements; nullopt: none
};

// A keyword argument naming one value of an enum (enum_names.h); throws
// std::invalid_argument naming the field and the choices otherwise.
template <typename Enum, std::size_t N>
Enum EnumArgument(const EnumNames<Enum, N>& names, const std::string& text) {
  Enum value{};
  std::string why;
  if (!names.Parse(text, &value, &why)) throw std::invalid_argument(why);
  return value;
}

// A base_pose keyword argument: None (the identity) or (x, y, z, roll, pitch,
// yaw) [m, rad]. Throws std::invalid_argument naming base_pose.
BasePose BasePoseArgument(const py::object& value);

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ArrayRef = Eigen::Ref<const RowMatrix>;

// An n_samples × n_dof array (a 1-D array is one joint's column) with a name
// for messages; throws std::invalid_argument otherwise (log_bindings.cc).
void CheckJointArray(const std::string& name, const Eigen::MatrixXd& x, Eigen::Index n_samples, int n_dof);

// {t, q, [qd, qdd], tau} as numpy arrays (log_bindings.cc).
py::dict JointLogToDict(JointLog log);

// A log given as a file path (read as `identify` reads it) or as a dict of
// arrays; `source` names it in messages (log_bindings.cc).
PreparedLog PrepareLogArgument(const py::object& log, const std::string& source, const RobotModel& model,
                               const LogPreparationOptions& options);

// Each adds its part of the module to `m`, in this order (the order of help(idbench)).
// A library message with its option fields spelled as this module's keyword
// arguments (locked_joints → lock, plausibility.total_mass → total_mass);
// errors raised to Python pass through it (idbench_module.cc).
std::string KeywordSpelling(const std::string& message);

void BindRobot(py::module_& m);
void BindIdentify(py::module_& m);
void BindPayload(py::module_& m);
void BindLog(py::module_& m);
void BindDesign(py::module_& m);
void BindRender(py::module_& m);

}  // namespace idbench::python
