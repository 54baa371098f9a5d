#include "idbench/engine/robot_model.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace idbench {
namespace {

void Check(bool ok, const std::string& model, const Link& link, const std::string& what) {
  if (!ok) {
    throw std::invalid_argument("robot '" + model + "', link '" + link.name + "': " + what);
  }
}

}  // namespace

RobotModel::RobotModel(std::string name, std::vector<Link> links, Eigen::Vector3d g_W, std::vector<GroundLink> ground)
    : name_(std::move(name)), links_(std::move(links)), g_W_(g_W), ground_(std::move(ground)) {
  if (links_.empty()) throw std::invalid_argument("robot '" + name_ + "': no links");
  children_.assign(links_.size() + 1, {});
  for (int i = 0; i < n_links(); ++i) {
    const Link& link = links_[static_cast<size_t>(i)];
    Check(link.parent >= -1 && link.parent < i, name_, link,
          "parent index must be in [-1, " + std::to_string(i - 1) + "], got " +
              std::to_string(link.parent));
    Check(std::abs(link.axis_J.norm() - 1.0) < 1e-9, name_, link, "joint axis must be a unit vector");
    Check(std::isfinite(link.inertia.mass) && link.inertia.mass > 0.0, name_, link,
          "mass must be > 0, got " + std::to_string(link.inertia.mass));
    const Eigen::Matrix3d& I = link.inertia.I_Bcm_B;
    Check(I.allFinite() && (I - I.transpose()).norm() <= 1e-12 * I.norm(), name_, link,
          "inertia tensor must be symmetric");
    Check(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues().minCoeff() > 0.0, name_, link,
          "inertia tensor must be positive definite");
    Check(link.limits.q_min < link.limits.q_max, name_, link, "joint limits need q_min < q_max");
    Check(link.limits.qd_max > 0.0 && link.limits.qdd_max > 0.0 && link.limits.tau_max > 0.0, name_,
          link, "velocity, acceleration and torque limits must be > 0");
    const JointDynamics& dyn = link.dynamics;
    Check(dyn.viscous >= 0.0 && dyn.coulomb >= 0.0 && dyn.rotor_inertia >= 0.0, name_, link,
          "joint friction and rotor inertia must be >= 0");
    children_[static_cast<size_t>(link.parent + 1)].push_back(i);
  }
}

std::vector<std::string> InertiaWarnings(const RobotModel& model) {
  std::vector<std::string> warnings;
  for (const Link& link : model.links()) {
    const Eigen::Vector3d d =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(link.inertia.I_Bcm_B).eigenvalues();  // ascending
    // Principal moments of a real body satisfy a + b ≥ c; sorted ascending,
    // only the two smallest against the largest can fail.
    if (d[0] + d[1] < d[2] - 1e-9 * d.sum()) {
      std::ostringstream message;
      message << "robot '" << model.name() << "', link '" << link.name << "': principal moments of inertia " << d[0] << ", " << d[1] << ", " << d[2]
              << " violate the triangle inequality (" << d[0] << " + " << d[1] << " < " << d[2]
              << "); no rigid body has this inertia";
      warnings.push_back(message.str());
    }
  }
  return warnings;
}

}  // namespace idbench
