// Joint logs between Python and the library: arrays or a CSV path in
// (PrepareLogArgument), numpy arrays out; idbench.simulate.
#include <optional>
#include <stdexcept>

#include "bindings.h"
#include "idbench/workbench/commands/simulate_command.h"

namespace idbench::python {

void CheckJointArray(const std::string& name, const Eigen::MatrixXd& x, Eigen::Index n_samples, int n_dof) {
  if (x.rows() != n_samples || x.cols() != n_dof) {
    throw std::invalid_argument(name + ": expected an array of " + std::to_string(n_samples) + " samples × " +
                                std::to_string(n_dof) + " joints, got " + std::to_string(x.rows()) + " × " +
                                std::to_string(x.cols()));
  }
  if (!x.allFinite()) throw std::invalid_argument(name + ": not every value is a finite number");
}

py::dict JointLogToDict(JointLog log) {
  py::dict out;
  out["t"] = std::move(log.t);
  out["q"] = std::move(log.q);
  if (log.qd.size() > 0) out["qd"] = std::move(log.qd);
  if (log.qdd.size() > 0) out["qdd"] = std::move(log.qdd);
  out["tau"] = std::move(log.tau);
  return out;
}

PreparedLog PrepareLogArgument(const py::object& log, const std::string& source, const RobotModel& model,
                               const LogPreparationOptions& options) {
  if (py::isinstance<py::str>(log) || py::hasattr(log, "__fspath__")) {
    return PrepareJointLog(py::str(log).cast<std::string>(), model, options);
  }
  // A dict of arrays, read as a file is (angle_unit, drive_gains, limits):
  // a 1-D array is one joint's column.
  if (!py::isinstance<py::dict>(log)) {
    throw std::invalid_argument(source + ": expected a CSV path or a dict of arrays {t, q, [qd, qdd], tau | i}");
  }
  std::map<std::string, Eigen::MatrixXd> arrays;
  for (const auto& [key, value] : log.cast<py::dict>()) {
    if (value.is_none()) continue;
    const std::string name = py::str(key).cast<std::string>();
    try {
      arrays[name] = value.cast<RowMatrix>();
    } catch (const py::cast_error&) {
      throw py::type_error(source + "['" + name + "']: expected an array of numbers, got " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    }
  }
  return PrepareRecordedJointLog(RecordedJointLogFromArrays(arrays, model, source, options.format, options.torques),
                                 source, options);
}

void BindLog(py::module_& m) {
  const SimulateOptions sim_defaults;
  m.def(
      "simulate",
      [](const Robot& robot, const std::string& trajectory, double duration, double paper_accel, double dt,
         double rate, const std::vector<double>& tau_noise, double tau_noise_bandwidth, double q_noise, double q_resolution, bool derivatives,
         unsigned seed, const py::object& base_pose, const std::string& transmission,
         const std::vector<double>& motor_viscous, const std::vector<double>& motor_coulomb,
         const std::vector<double>& motor_rotor_inertia) {
        SimulateOptions options;
        options.base_pose = BasePoseArgument(base_pose);
        options.robot = robot.source;
        options.trajectory = trajectory;
        options.duration = duration;
        options.paper_accel_deg_s2 = paper_accel;
        options.dt = dt;
        options.sensors.rate_hz = rate;
        options.sensors.tau_noise = tau_noise;
        options.sensors.tau_noise_bandwidth_hz = tau_noise_bandwidth;
        options.sensors.q_noise = q_noise;
        options.sensors.q_resolution = q_resolution;
        options.sensors.record_derivatives = derivatives;
        options.sensors.seed = seed;
        options.transmission = transmission;
        options.motor_viscous = motor_viscous;
        options.motor_coulomb = motor_coulomb;
        options.motor_rotor_inertia = motor_rotor_inertia;
        std::string why;
        if (!options.IsValid(&why)) throw std::invalid_argument(why);
        if (!options.sensors.IsValid(robot.model->n_dof(), options.dt, &why)) throw std::invalid_argument(why);
        const std::optional<Transmission> through =
            SimulateTransmission(options, robot.model->n_dof(), robot.transmission);
        if (!through) {
          JointLog log;
          {
            py::gil_scoped_release release;
            log = SimulateJointLog(*robot.model, options);
          }
          return JointLogToDict(std::move(log));
        }
        // On the motor side: the joint-side arrays (noise-free, τ = Aᵀ·τm) and the motors' qm, qdm, taum.
        std::optional<MotorSideLog> log;
        {
          py::gil_scoped_release release;
          log = SimulateMotorSideLog(*robot.model, *through, options);
        }
        py::dict out = JointLogToDict(std::move(log->joint));
        out["qm"] = std::move(log->motor.q);
        if (log->motor.qd.size() > 0) out["qdm"] = std::move(log->motor.qd);
        out["taum"] = std::move(log->motor.tau);
        return out;
      },
      py::arg("robot"), py::arg("trajectory") = sim_defaults.trajectory, py::kw_only(),
      py::arg("duration") = sim_defaults.duration, py::arg("paper_accel") = sim_defaults.paper_accel_deg_s2,
      py::arg("dt") = sim_defaults.dt, py::arg("rate") = sim_defaults.sensors.rate_hz,
      py::arg("tau_noise") = std::vector<double>{},
      py::arg("tau_noise_bandwidth") = sim_defaults.sensors.tau_noise_bandwidth_hz, py::arg("q_noise") = sim_defaults.sensors.q_noise,
      py::arg("q_resolution") = sim_defaults.sensors.q_resolution,
      py::arg("derivatives") = sim_defaults.sensors.record_derivatives, py::arg("seed") = sim_defaults.sensors.seed,
      py::arg("base_pose") = py::none(), py::arg("transmission") = sim_defaults.transmission,
      py::arg("motor_viscous") = std::vector<double>{}, py::arg("motor_coulomb") = std::vector<double>{},
      py::arg("motor_rotor_inertia") = std::vector<double>{},
      "Simulates the robot along a built-in motion or a trajectory file in Bullet (as `idbench simulate`), its base "
      "at base_pose=(x, y, z, roll, pitch, yaw) [m, rad] when given; torque noise tau_noise [N m], white or low-pass "
      "coloured to tau_noise_bandwidth [Hz] (sigma unchanged); "
      "returns {t, q, [qd, qdd], tau} as numpy arrays. With transmission (\"urdf\" or a file, as `idbench "
      "simulate --transmission`) and the motors' own motor_viscous, motor_coulomb, motor_rotor_inertia (one value "
      "or one per motor), also the motor side, qm = A·(q − q0), [qdm = A·qd], taum = A⁻ᵀ·tau, where the sensors' "
      "noise applies; the joint-side arrays are then noise-free (tau = Aᵀ·taum)");
}

}  // namespace idbench::python
