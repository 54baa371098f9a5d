#include "idbench/ident/base_parameters.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

namespace idbench {

Eigen::MatrixXd BaseParameters::Reduce(const Eigen::MatrixXd& Y) const {
  Eigen::MatrixXd Yb(Y.rows(), n_base());
  for (int k = 0; k < n_base(); ++k) Yb.col(k) = Y.col(independent[static_cast<size_t>(k)]);
  return Yb;
}

BaseParameters ComputeBaseParameters(const RobotModel& model, const FrictionModel& friction,
                                     const BaseParameterOptions& options) {
  if (std::string why; !friction.IsValid(&why)) throw std::invalid_argument(why);
  const int n = model.n_dof();
  const int p = NumStandardParameters(model, friction);
  // 1. Stack the regressor over random states.
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd W(options.n_samples * n, p), Y;
  Eigen::VectorXd q(n), qd(n), qdd(n);
  RobotData data(model);
  for (int s = 0; s < options.n_samples; ++s) {
    for (int j = 0; j < n; ++j) {
      q[j] = options.q_range * u(rng);
      qd[j] = options.qd_range * u(rng);
      qdd[j] = options.qdd_range * u(rng);
    }
    ComputeJointTorqueRegressor(model, friction, q, qd, qdd, &data, &Y);
    W.middleRows(s * n, n) = Y;
  }
  // 2. Zero columns, then QR with column pivoting of the normalised rest. A
  // column is zero against the largest of its kind: the inertial ones, or the
  // friction and rotor ones, which a transmission scales by N and N² (a
  // reduction of 1e4 makes them 1e8 times the inertial ones; against those
  // every inertial column would read as zero).
  const Eigen::VectorXd norms = W.colwise().norm();
  const int n_inertial = std::min(p, model.n_links() * kInertialParametersPerLink);
  const double max_inertial = n_inertial > 0 ? norms.head(n_inertial).maxCoeff() : 0.0;
  const double max_friction = p > n_inertial ? norms.tail(p - n_inertial).maxCoeff() : 0.0;
  BaseParameters base;
  std::vector<int> live;
  for (int c = 0; c < p; ++c) {
    const double max_norm = c < n_inertial ? max_inertial : max_friction;
    if (norms[c] > options.rank_tolerance * max_norm) live.push_back(c);
    else base.unexcited.push_back(c);
  }
  // The independent columns, chosen from the last column backwards (friction
  // terms first, then the outer links): a column joins the base set when its
  // normalised residual against the columns already chosen exceeds the
  // tolerance. Unlike the pivot order of a column-pivoted QR, this
  // choice does not depend on rounding among equivalent columns (e.g. Izz of
  // link 1 and the rotor inertia of joint 1), so the base set, and cond(W_b),
  // are the same on every build.
  Eigen::MatrixXd Q(W.rows(), 0);
  for (auto it = live.rbegin(); it != live.rend(); ++it) {
    const int c = *it;
    Eigen::VectorXd r = W.col(c) / norms[c];
    for (int pass = 0; pass < 2; ++pass) r -= Q * (Q.transpose() * r);  // twice: re-orthogonalise
    const double residual = r.norm();
    if (residual <= options.rank_tolerance) continue;  // a dependent column: rounding, ~1e-14
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = r / residual;
    base.independent.push_back(c);
  }
  std::sort(base.independent.begin(), base.independent.end());
  const int rank = base.n_base();

  // 3. K from W_d = W_b K (W_b has full column rank).
  std::vector<int> dependent;
  for (int c : live) {
    if (!std::binary_search(base.independent.begin(), base.independent.end(), c)) dependent.push_back(c);
  }
  const Eigen::MatrixXd Wb = base.Reduce(W);
  Eigen::MatrixXd Wd(W.rows(), static_cast<int>(dependent.size()));
  for (size_t c = 0; c < dependent.size(); ++c) Wd.col(static_cast<int>(c)) = W.col(dependent[c]);
  // On normalised columns (K = D_b⁻¹·(W_b D_b⁻¹)⁺·W_d): the pivoting QR's
  // rank threshold would otherwise drop the small columns beside N²-scaled ones.
  Eigen::VectorXd scale_b(rank);
  for (int k = 0; k < rank; ++k) scale_b[k] = norms[base.independent[static_cast<size_t>(k)]];
  const Eigen::MatrixXd K =
      scale_b.cwiseInverse().asDiagonal() * (Wb * scale_b.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(Wd);

  // 4. β = π_b + K π_d, with readable names.
  const std::vector<std::string> names = StandardParameterNames(model, friction);
  base.combination = Eigen::MatrixXd::Zero(rank, p);
  for (int k = 0; k < rank; ++k) {
    const int b = base.independent[static_cast<size_t>(k)];
    base.combination(k, b) = 1.0;
    std::string name = names[static_cast<size_t>(b)];
    for (size_t c = 0; c < dependent.size(); ++c) {
      double v = K(k, static_cast<int>(c));
      if (std::abs(v) < 1e-9) continue;
      base.combination(k, dependent[c]) = v;
      char term[96];
      std::snprintf(term, sizeof(term), " %s %.6g %s", v < 0 ? "-" : "+", std::abs(v), names[dependent[c]].c_str());
      name += term;
    }
    base.names.push_back(name);
  }
  return base;
}

}  // namespace idbench
