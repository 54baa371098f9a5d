#include "idbench/excitation/actuator_limits.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "excitation_design_internal.h"

namespace idbench {

using internal::Format;

void ActuatorLimits::Check(int n_dof) const {
  if (empty()) return;
  std::string why;
  if (!transmission.IsValid(n_dof, &why)) throw std::invalid_argument("transmission: " + why);
  if (static_cast<int>(motors.size()) != n_dof) {
    throw std::invalid_argument("actuators: expected " + std::to_string(n_dof) + " entries (one per motor), got " +
                                std::to_string(motors.size()));
  }
  for (size_t k = 0; k < motors.size(); ++k) {
    const std::string where = "actuators[" + std::to_string(k) + "].";
    if (!(motors[k].qd_max > 0.0)) throw std::invalid_argument(where + Format("qd_max: must be > 0, got %g", motors[k].qd_max));
    if (!(motors[k].tau_max > 0.0)) throw std::invalid_argument(where + Format("tau_max: must be > 0, got %g", motors[k].tau_max));
  }
}

Eigen::MatrixXd ActuatorLimits::MotorTorqueFromJoint() const {
  return transmission.actuator_from_joint.transpose().inverse();
}

std::string ActuatorLimits::DrivenJoints(const RobotModel& model, int motor) const {
  std::string out;
  const Eigen::MatrixXd& A = transmission.actuator_from_joint;
  for (int j = 0; j < A.cols(); ++j) {
    if (A(motor, j) != 0.0) out += (out.empty() ? "" : ", ") + model.link(j).joint_name;
  }
  return out;
}

}  // namespace idbench
