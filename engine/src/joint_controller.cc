#include "idbench/engine/joint_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "idbench/engine/inverse_dynamics.h"

namespace idbench {
namespace {

// A gain field as one value per joint: one value repeated, n as given, empty
// as `empty_value`.
Eigen::VectorXd PerJoint(const std::vector<double>& values, int n_dof, double empty_value) {
  if (values.empty()) return Eigen::VectorXd::Constant(n_dof, empty_value);
  if (values.size() == 1) return Eigen::VectorXd::Constant(n_dof, values[0]);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

bool JointControllerOptions::IsValid(int n_dof, std::string* why) const {
  const std::pair<const char*, const std::vector<double>*> fields[] = {
      {"kp", &kp}, {"kd", &kd}, {"ki", &ki}, {"tau_max", &tau_max}};
  for (const auto& [name, values] : fields) {
    const std::string field(name);
    if ((field == "kp" || field == "kd") && values->empty()) {
      if (why) *why = field + ": expected one value or " + std::to_string(n_dof) + " (one per joint), got none";
      return false;
    }
    if (values->size() > 1 && static_cast<int>(values->size()) != n_dof) {
      if (why) {
        *why = field + ": expected one value or " + std::to_string(n_dof) + " (one per joint), got " +
               std::to_string(values->size());
      }
      return false;
    }
    for (size_t j = 0; j < values->size(); ++j) {
      const double v = (*values)[j];
      const bool ok = field == "tau_max" ? (std::isfinite(v) && v > 0.0) : (std::isfinite(v) && v >= 0.0 && v <= kMaxGain);
      if (!ok) {
        if (why) {
          *why = field + "[" + std::to_string(j) + "]: expected " +
                 (field == "tau_max" ? std::string("a finite limit > 0 N m") : std::string("a gain in [0, 1e12]")) +
                 ", got " + std::to_string(v);
        }
        return false;
      }
    }
  }
  return true;
}

JointController::JointController(const JointControllerOptions& options, const RobotModel& model,
                                 double sample_period)
    : model_(model), period_(sample_period), feedforward_(options.model_feedforward), data_(model) {
  const int n = model.n_dof();
  std::string why;
  if (!options.IsValid(n, &why)) throw std::invalid_argument("controller: " + why);
  if (!(sample_period > 0.0) || !std::isfinite(sample_period)) {
    throw std::invalid_argument("controller: expected a sample period > 0 s, got " + std::to_string(sample_period));
  }
  kp_ = PerJoint(options.kp, n, 0.0);
  kd_ = PerJoint(options.kd, n, 0.0);
  ki_ = PerJoint(options.ki, n, 0.0);
  tau_max_ = PerJoint(options.tau_max, n, std::numeric_limits<double>::infinity());
  integral_ = Eigen::VectorXd::Zero(n);
  error_ = Eigen::VectorXd::Zero(n);
  previous_error_ = Eigen::VectorXd::Zero(n);
  reference_ = JointState(n);
  feedforward_state_ = JointState(n);
}

void JointController::Reset() {
  integral_.setZero();
  previous_error_.setZero();
  started_ = false;
}

void JointController::Command(const Trajectory& reference, double t, const Eigen::VectorXd& q_measured,
                              Eigen::VectorXd* tau) {
  const int n = model_.n_dof();
  if (q_measured.size() != n || reference.n_dof() != n) {
    throw std::invalid_argument("JointController::Command: expected " + std::to_string(n) + " joint values, got " +
                                std::to_string(q_measured.size()) + " and a reference of " +
                                std::to_string(reference.n_dof()));
  }
  reference.Evaluate(t, &reference_);
  // Feed-forward along the reference at the middle of the hold, from the controller's model.
  if (feedforward_) {
    reference.Evaluate(std::min(t + 0.5 * period_, reference.duration()), &feedforward_state_);
    *tau = InverseDynamics(model_, feedforward_state_.q, feedforward_state_.qd, feedforward_state_.qdd, &data_);
    AddJointDynamicsTorque(model_, feedforward_state_.qd, feedforward_state_.qdd, tau);
  } else {
    tau->setZero(n);
  }
  // PID on the measured error; the derivative is the backward difference.
  error_ = reference_.q - q_measured;
  if (!started_) previous_error_ = error_;
  started_ = true;
  for (int j = 0; j < n; ++j) {
    const double derivative = (error_[j] - previous_error_[j]) / period_;
    const double candidate_integral = integral_[j] + period_ * error_[j];
    const double unclamped = (*tau)[j] + kp_[j] * error_[j] + kd_[j] * derivative + ki_[j] * candidate_integral;
    const double clamped = std::clamp(unclamped, -tau_max_[j], tau_max_[j]);
    // Conditional integration: the integral only grows while the joint is not saturated.
    if (clamped == unclamped) integral_[j] = candidate_integral;
    (*tau)[j] = clamped;
  }
  previous_error_ = error_;
}

}  // namespace idbench
