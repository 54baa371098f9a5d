#include "idbench/ident/physically_consistent.h"

#include <Eigen/Eigenvalues>
#include <stdexcept>
#include <string>

#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {
namespace {

constexpr int kP = kInertialParametersPerLink;

std::string Size(Eigen::Index n) { return std::to_string(n); }

}  // namespace

Eigen::Matrix4d PseudoInertia(const Eigen::Ref<const Eigen::VectorXd>& pi10) {
  if (pi10.size() != kP) {
    throw std::invalid_argument("PseudoInertia: expected 10 parameters, got " + Size(pi10.size()));
  }
  const double m = pi10[0], ixx = pi10[4], ixy = pi10[5], iyy = pi10[6], ixz = pi10[7], iyz = pi10[8],
               izz = pi10[9];
  const double half_trace = 0.5 * (ixx + iyy + izz);
  Eigen::Matrix4d J;
  J << half_trace - ixx, -ixy, -ixz, pi10[1],  //
      -ixy, half_trace - iyy, -iyz, pi10[2],   //
      -ixz, -iyz, half_trace - izz, pi10[3],   //
      pi10[1], pi10[2], pi10[3], m;
  return J;
}

Eigen::VectorXd MinPseudoInertiaEigenvalues(const Eigen::VectorXd& pi, int n_links) {
  if (n_links < 0 || pi.size() < kP * n_links) {
    throw std::invalid_argument("MinPseudoInertiaEigenvalues: expected at least " + Size(kP * n_links) +
                                " parameters, got " + Size(pi.size()));
  }
  Eigen::VectorXd min_eigenvalue(n_links);
  for (int l = 0; l < n_links; ++l) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(PseudoInertia(pi.segment<kP>(kP * l)),
                                                             Eigen::EigenvaluesOnly);
    min_eigenvalue[l] = eig.eigenvalues()[0];
  }
  return min_eigenvalue;
}

}  // namespace idbench
