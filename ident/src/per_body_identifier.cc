#include "idbench/ident/per_body_identifier.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "idbench/ident/per_body_regressor.h"

namespace idbench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// K_i X_i = L_i of one body (eq. 24): Newton rows then Euler rows per sample.
struct BodySystem {
  Eigen::MatrixXd newton_K;  // 3 n × 1 (world axes interleaved)
  Eigen::VectorXd newton_L;
  Eigen::MatrixXd euler_K;   // 3 n × 3
  Eigen::VectorXd euler_L;
};

void CheckInputs(const RobotModel& model, const SimulationLog& log, const std::vector<int>& steps) {
  CheckPrincipalAxes(model, "per-body identification");
  if (steps.empty()) throw std::invalid_argument("per-body identification: no samples");
  for (int s : steps) {
    if (s < 0 || s >= static_cast<int>(log.steps.size())) {
      throw std::invalid_argument("per-body identification: sample index " + std::to_string(s) +
                                  " outside the log (0.." + std::to_string(log.steps.size() - 1) + ")");
    }
  }
}

BodySystem StackBody(const RobotModel& model, int body, const SimulationLog& log, const std::vector<int>& steps) {
  const int n = static_cast<int>(steps.size());
  BodySystem sys{Eigen::MatrixXd(3 * n, 1), Eigen::VectorXd(3 * n), Eigen::MatrixXd(3 * n, 3),
                 Eigen::VectorXd(3 * n)};
  for (int k = 0; k < n; ++k) {
    const PerBodyRows rows = ComputePerBodyRows(model, body, log.steps[static_cast<size_t>(steps[k])]);
    sys.newton_K.block<3, 1>(3 * k, 0) = rows.newton_regressor;
    sys.newton_L.segment<3>(3 * k) = rows.newton_force;
    sys.euler_K.block<3, 3>(3 * k, 0) = rows.euler_regressor;
    sys.euler_L.segment<3>(3 * k) = rows.euler_moment;
  }
  return sys;
}

ParameterResult MakeResult(const std::string& name, double truth, const LeastSquaresSolution& sol, int j) {
  ParameterResult p;
  p.name = name;
  p.true_value = truth;
  p.identifiable = sol.identifiable[static_cast<size_t>(j)];
  p.reason = sol.reason[static_cast<size_t>(j)];
  p.identified = p.identifiable ? sol.x[j] : kNaN;
  p.abs_error = p.identifiable ? p.identified - truth : kNaN;
  p.rel_error = p.identifiable ? std::abs(p.abs_error) / std::abs(truth) : kNaN;
  return p;
}

BlockReport MakeBlock(const LeastSquaresSolution& sol, int n_unknowns) {
  return BlockReport{sol.rank, n_unknowns, sol.cond, sol.residual_norm};
}

}  // namespace

PerBodyIdentificationResult IdentifyPerBody(const RobotModel& model, const SimulationLog& log,
                                            const std::vector<int>& steps, const LeastSquaresOptions& options) {
  CheckInputs(model, log, steps);
  PerBodyIdentificationResult result;
  result.n_samples = static_cast<int>(steps.size());
  const int n = result.n_samples;
  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);
    const BodySystem sys = StackBody(model, i, log, steps);
    BodyResult body;
    body.name = link.name;

    // Mass per world axis (Table 2): the rows of one axis alone. A column is
    // "zero" relative to the regressor of all three axes.
    LeastSquaresOptions axis_options = options;
    axis_options.column_norm_reference = sys.newton_K.norm();
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::MatrixXd K(n, 1);
      Eigen::VectorXd L(n);
      for (int k = 0; k < n; ++k) {
        K(k, 0) = sys.newton_K(3 * k + axis, 0);
        L[k] = sys.newton_L[3 * k + axis];
      }
      const std::string name = PerBodyParameterNames()[static_cast<size_t>(axis)];
      const LeastSquaresSolution sol = SolveLeastSquares(K, L, {name}, axis_options);
      body.parameters.push_back(MakeResult(name, link.inertia.mass, sol, 0));
    }
    // Mass from all Newton rows.
    const LeastSquaresSolution mass = SolveLeastSquares(sys.newton_K, sys.newton_L, {"m"}, options);
    body.parameters.push_back(MakeResult("m", link.inertia.mass, mass, 0));
    body.newton = MakeBlock(mass, 1);
    // Principal moments (Table 3).
    const std::vector<std::string> j_names{"J11", "J22", "J33"};
    const LeastSquaresSolution inertia = SolveLeastSquares(sys.euler_K, sys.euler_L, j_names, options);
    for (int j = 0; j < 3; ++j) {
      body.parameters.push_back(MakeResult(j_names[static_cast<size_t>(j)], link.inertia.I_Bcm_B(j, j), inertia, j));
    }
    body.euler = MakeBlock(inertia, 3);

    for (const ParameterResult& p : body.parameters) {
      if (p.identifiable && p.rel_error >= result.max_rel_error) {
        result.max_rel_error = p.rel_error;
        result.max_rel_error_at = body.name + "." + p.name;
      }
    }
    result.bodies.push_back(std::move(body));
  }
  return result;
}

}  // namespace idbench
