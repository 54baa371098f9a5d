#include "idbench/workbench/commands/simulate_command.h"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/controller_file.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/formats/transmission_file.h"

namespace idbench {

SimulationOptions SimulateOptions::simulation() const {
  SimulationOptions sim;
  sim.dt = dt;
  sim.duration = duration;
  return sim;
}

bool SimulateOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  std::string sim_why;
  if (!simulation().IsValid(&sim_why)) return fail(sim_why);
  if (!std::isfinite(paper_accel_deg_s2) || paper_accel_deg_s2 <= 0.0)
    return fail("paper_accel_deg_s2: must be > 0 deg/s^2, got " + std::to_string(paper_accel_deg_s2));
  if (!base_pose.IsValid(why)) return false;
  if (std::string out_why; !IsUsableOutputFile(out, "out", &out_why)) return fail(out_why);
  const std::vector<std::string> outputs = Outputs();
  if (outputs.size() > 1 && outputs[1] == out) {
    return fail("out: a motor-side log's CSV cannot end in .json (its description does), got '" + out + "'");
  }
  // An input the run would overwrite (its own trajectory, a design's
  // trajectory.json beside the log, the transmission file).
  if (!controller.empty() && !transmission.empty()) {
    return fail("controller: a closed loop is simulated on the joint side; it cannot be combined with a "
                "transmission");
  }
  const std::pair<const char*, const std::string*> inputs[] = {
      {"robot", &robot}, {"trajectory", &trajectory}, {"transmission", &transmission}, {"controller", &controller}};
  for (size_t k = 0; k < outputs.size(); ++k) {
    for (const auto& [field, path] : inputs) {
      if (path->empty() || !IsSameFile(outputs[k], *path)) continue;
      return fail(std::string("out: ") + (k == 0 ? "'" + out + "'" : "its description '" + outputs[k] + "'") +
                  " would overwrite the " + field + " file '" + *path + "'");
    }
  }
  return true;
}

std::vector<std::string> SimulateOptions::Outputs() const {
  std::vector<std::string> outputs{out};
  if (!transmission.empty()) outputs.push_back(std::filesystem::path(out).replace_extension(".json").string());
  return outputs;
}

namespace {

// The experiment's model (mounted at options.base_pose, gravity seen from
// the base), motion and simulation options, the sensors checked.
struct Experiment {
  RobotModel model;
  std::unique_ptr<Trajectory> motion;
  SimulationOptions simulation;
};
Experiment PrepareExperiment(const RobotModel& loaded, const SimulateOptions& options) {
  Experiment e{MountRobot(loaded, options.base_pose), nullptr, options.simulation()};
  std::string why;
  if (!options.sensors.IsValid(e.model.n_dof(), options.dt, &why)) throw std::invalid_argument("sensors: " + why);
  const BuiltinMotionOptions builtin{.duration = options.duration,
                                     .paper_qdd = options.paper_accel_deg_s2 * std::numbers::pi / 180.0};
  e.motion = LoadTrajectoryArg(options.trajectory, e.model, builtin);
  e.simulation.duration = e.motion->duration();  // a file's own
  return e;
}

// The simulation before the sensors.
SimulationLog SimulateSteps(const RobotModel& loaded, const SimulateOptions& options) {
  const Experiment e = PrepareExperiment(loaded, options);
  return Simulate(e.model, *e.motion, e.simulation);
}

// A motor_* field as one value per motor: one value repeated, n as given,
// empty as zeros. Throws std::invalid_argument naming the field.
Eigen::VectorXd PerMotor(const std::vector<double>& values, int n, const std::string& field) {
  if (values.empty()) return Eigen::VectorXd::Zero(n);
  if (values.size() != 1 && static_cast<int>(values.size()) != n) {
    throw std::invalid_argument(field + ": expected one value or " + std::to_string(n) + " (one per motor), got " +
                                std::to_string(values.size()));
  }
  Eigen::VectorXd out(n);
  for (int k = 0; k < n; ++k) {
    out[k] = values[values.size() == 1 ? 0 : static_cast<size_t>(k)];
    if (!std::isfinite(out[k]) || out[k] < 0.0) {
      throw std::invalid_argument(field + ": expected finite values >= 0, got " + std::to_string(out[k]));
    }
  }
  return out;
}

}  // namespace

JointLog SimulateJointLog(const RobotModel& loaded, const SimulateOptions& options) {
  return Measure(SimulateSteps(loaded, options), options.sensors);
}

ClosedLoopLog SimulateClosedLoopLog(const RobotModel& loaded, const SimulateOptions& options) {
  const Experiment e = PrepareExperiment(loaded, options);
  const JointControllerOptions controller = ReadControllerFile(options.controller, e.model.n_dof());
  return SimulateClosedLoop(e.model, *e.motion, e.simulation, controller, options.sensors);
}

std::optional<std::string> LostTrackingWarning(const RobotModel& model, const ClosedLoopLog& closed) {
  if (closed.log.n_samples() == 0) return std::nullopt;
  Eigen::Index sample = 0, joint = 0;
  const double largest = (closed.log.q - closed.q_ref).cwiseAbs().maxCoeff(&sample, &joint);
  if (!(largest > kLostTrackingRad)) return std::nullopt;
  const Link& link = model.link(static_cast<int>(joint));
  const std::string name = link.joint_name.empty() ? link.name : link.joint_name;
  char text[320];
  std::snprintf(text, sizeof text, "the controller did not hold the reference: joint '%s' %.3g rad from it at t = "
                "%.4g s (more than %g rad); the log is of the motion that happened, not of the reference",
                name.c_str(), largest, closed.log.t[sample], kLostTrackingRad);
  return std::string(text);
}

std::optional<Transmission> SimulateTransmission(const SimulateOptions& options, int n_dof,
                                                 const std::optional<Transmission>& from_urdf) {
  if (options.transmission.empty()) {
    if (!options.motor_viscous.empty() || !options.motor_coulomb.empty() || !options.motor_rotor_inertia.empty()) {
      throw std::invalid_argument("motor_viscous, motor_coulomb, motor_rotor_inertia: the motors' terms need a "
                                  "transmission to act through");
    }
    return std::nullopt;
  }
  return ReadTransmissionArg(options.transmission, options.robot, n_dof, from_urdf);
}

MotorSideLog SimulateMotorSideLog(const RobotModel& model, const Transmission& transmission,
                                  const SimulateOptions& options) {
  const int n = model.n_dof();
  std::string why;
  if (!transmission.IsValid(n, &why)) throw std::invalid_argument("transmission: " + why);
  const Eigen::VectorXd Fv = PerMotor(options.motor_viscous, n, "motor_viscous");
  const Eigen::VectorXd Fc = PerMotor(options.motor_coulomb, n, "motor_coulomb");
  const Eigen::VectorXd Ia = PerMotor(options.motor_rotor_inertia, n, "motor_rotor_inertia");
  const Eigen::MatrixXd& A = transmission.actuator_from_joint;
  const Eigen::VectorXd q0 =
      transmission.joint_offset.size() > 0 ? transmission.joint_offset : Eigen::VectorXd::Zero(n);
  const Eigen::PartialPivLU<Eigen::MatrixXd> At(Eigen::MatrixXd(A.transpose()));

  // Each step: the motors' terms into the joint torques (τ += Aᵀ·τm_own),
  // then the step on the motor side, where the sensors sit.
  SimulationLog steps = SimulateSteps(model, options);
  SimulationLog joint_steps = steps;
  for (size_t s = 0; s < steps.steps.size(); ++s) {
    LogStep& step = joint_steps.steps[s];
    const Eigen::VectorXd thetad = A * step.qd, thetadd = A * step.qdd;
    const Eigen::VectorXd sign = thetad.unaryExpr([](double v) { return double((v > 0.0) - (v < 0.0)); });
    const Eigen::VectorXd tau_own = Fv.cwiseProduct(thetad) + Fc.cwiseProduct(sign) + Ia.cwiseProduct(thetadd);
    step.tau += A.transpose() * tau_own;
    LogStep& motor = steps.steps[s];
    motor.q = A * (step.q - q0);
    motor.qd = thetad;
    motor.qdd = step.qdd;  // joint side: a log has no motor accelerations
    motor.tau = At.solve(step.tau);
  }
  MotorSideLog out;
  out.motor = Measure(steps, options.sensors);
  out.transmission = transmission;
  SensorOptions exact;
  exact.rate_hz = options.sensors.rate_hz;
  out.joint = Measure(joint_steps, exact);
  return out;
}

std::string FormatMotorSideLogCsv(const MotorSideLog& log) {
  // The joint-log writer's numbers under motor-side column names.
  const JointLog& rows = log.motor;
  std::string csv = FormatJointLogCsv(rows);
  std::string header = "t";
  for (const char* prefix : {"qm", "qdm", "qdd", "taum"}) {
    if (!rows.has_derivatives() && prefix[1] == 'd') continue;
    for (int j = 1; j <= rows.n_dof(); ++j) header += "," + std::string(prefix) + std::to_string(j);
  }
  return header + csv.substr(csv.find('\n'));
}

std::string FormatMotorSideLogDescription(const MotorSideLog& log, const std::string& csv_path) {
  // One row of A per line, so that the coupling reads as a matrix.
  const Eigen::MatrixXd& a = log.transmission.actuator_from_joint;
  std::string rows;
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    const Eigen::VectorXd row = a.row(k).transpose();
    rows += std::string(k == 0 ? "" : ",\n                            ") +
            nlohmann::json(std::vector<double>(row.data(), row.data() + row.size())).dump();
  }
  std::string out = "{\n  \"files\": [{\"path\": " + nlohmann::json(csv_path).dump() +
                    "}],\n  \"transmission\": {\n    \"actuator_from_joint\": [" + rows + "]";
  if (log.transmission.joint_offset.size() > 0) {
    const Eigen::VectorXd& q0 = log.transmission.joint_offset;
    out += ",\n    \"joint_offset\": " + nlohmann::json(std::vector<double>(q0.data(), q0.data() + q0.size())).dump();
  }
  return out + "\n  }\n}\n";
}

}  // namespace idbench
