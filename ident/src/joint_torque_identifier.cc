#include "idbench/ident/joint_torque_identifier.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "idbench/engine/link_bounding_box.h"
#include "idbench/ident/residual_covariance.h"
#include "idbench/ident/total_least_squares.h"

namespace idbench {

namespace {

void CheckLog(const RobotModel& model, const JointLog& log) {
  const int n = model.n_dof();
  if (log.n_dof() != n || log.tau.cols() != n || log.tau.rows() != log.n_samples()) {
    throw std::invalid_argument("joint log has " + std::to_string(log.n_dof()) + " joints, robot '" +
                                model.name() + "' has " + std::to_string(n));
  }
  // Before the derivatives: an empty log has no qd, qdd either, and that is not what is wrong.
  if (log.n_samples() == 0) {
    throw std::invalid_argument("joint log has no samples (none in its time window, if it was cut to one): "
                                "nothing to stack equations from");
  }
  if (!log.has_derivatives()) {
    throw std::invalid_argument("joint log has no velocities and accelerations (qd, qdd): estimate them from q "
                                "first (zero-phase low-pass filtering and differentiation)");
  }
}

}  // namespace

std::vector<std::vector<int>> JointFactorColumns(const RobotModel& model, const FrictionModel& friction,
                                           const BaseParameters& base) {
  const int n_inertial = model.n_links() * kInertialParametersPerLink;
  std::vector<std::vector<int>> columns(static_cast<size_t>(model.n_dof()));
  for (int k = 0; k < base.n_base(); ++k) {
    const int c = base.independent[static_cast<size_t>(k)];
    if (c < n_inertial) {
      for (int j = c / kInertialParametersPerLink; j >= 0; j = model.link(j).parent) {
        columns[static_cast<size_t>(j)].push_back(k);
      }
    } else if (!friction.actuator_side()) {
      columns[static_cast<size_t>((c - n_inertial) / friction.per_joint())].push_back(k);
    } else {
      // Motor m's terms reach every joint it turns with (A(m, j) != 0).
      const int m = (c - n_inertial) / friction.per_joint();
      for (int j = 0; j < model.n_dof(); ++j) {
        if (friction.actuator_from_joint(m, j) != 0.0) columns[static_cast<size_t>(j)].push_back(k);
      }
    }
  }
  return columns;
}

namespace {

// Factors of samples [s_begin, s_end) of the log, from zero. `data`, `Y`,
// and `rows` (per joint) are the caller's workspace.
void FactorSamples(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                   const JointLog& log, int s_begin, int s_end, RobotData* data, Eigen::MatrixXd* Y,
                   std::vector<Eigen::MatrixXd>* rows, StackedFactors* factors) {
  constexpr int kBlock = 128;  // samples per fold
  const int n = model.n_dof();
  // Standard column of each factor column, per joint.
  std::vector<std::vector<int>> standard(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    JointRowFactor& f = factors->joints[static_cast<size_t>(j)];
    for (int k : f.columns) standard[static_cast<size_t>(j)].push_back(base.independent[static_cast<size_t>(k)]);
    f.T.setZero();
    f.n_rows = 0;
    (*rows)[static_cast<size_t>(j)].resize(kBlock, static_cast<Eigen::Index>(f.columns.size()) + 1);
  }
  Eigen::VectorXd q(n), qd(n), qdd(n);
  for (int s0 = s_begin; s0 < s_end; s0 += kBlock) {
    const int m = std::min(kBlock, s_end - s0);
    // Regressor rows of the block, gathered per joint, τ last.
    for (int s = 0; s < m; ++s) {
      q = log.q.row(s0 + s).transpose();
      qd = log.qd.row(s0 + s).transpose();
      qdd = log.qdd.row(s0 + s).transpose();
      ComputeJointTorqueRegressor(model, friction, q, qd, qdd, data, Y);
      for (int j = 0; j < n; ++j) {
        const std::vector<int>& cols = standard[static_cast<size_t>(j)];
        Eigen::MatrixXd& r = (*rows)[static_cast<size_t>(j)];
        const Eigen::Index c = static_cast<Eigen::Index>(cols.size());
        for (Eigen::Index k = 0; k < c; ++k) r(s, k) = (*Y)(j, cols[static_cast<size_t>(k)]);
        r(s, c) = log.tau(s0 + s, j);
      }
    }
    // Fold them into each joint's factor.
    for (int j = 0; j < n; ++j) {
      FoldJointRows((*rows)[static_cast<size_t>(j)].topRows(m), &factors->joints[static_cast<size_t>(j)]);
    }
  }
}

void CheckEnoughEquations(Eigen::Index n_samples, int n_dof, int n_base) {
  if (n_samples * n_dof <= n_base) {
    throw std::invalid_argument("joint log has " + std::to_string(n_samples) + " usable samples (" +
                                std::to_string(n_samples * n_dof) + " equations) for " + std::to_string(n_base) +
                                " base parameters; record more samples");
  }
}

// The factors of a log's equations: streamed, or through W when the log is
// parallel-filtered (the filter runs along whole columns of W). Throws
// std::invalid_argument when there are no more equations than parameters.
StackedFactors FactorEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                               const JointLog& log, const std::optional<ParallelFilter>& filter) {
  if (!filter) {
    StackedFactors factors = FactorStackedEquations(model, friction, base, log);
    CheckEnoughEquations(factors.n_samples(), model.n_dof(), base.n_base());
    return factors;
  }
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model, friction, base, log, filter, &W, &tau);
  CheckEnoughEquations(W.rows() / model.n_dof(), model.n_dof(), base.n_base());
  return FactorStackedRows(W, tau, model.n_dof());
}

TorquePrediction Predict(const StackedFactors& factors, const Eigen::VectorXd& beta) {
  const Eigen::VectorXd residual = JointResidualNorms(factors, beta);
  const Eigen::VectorXd tau = JointResidualNorms(factors, Eigen::VectorXd::Zero(beta.size()));
  TorquePrediction out;
  out.joint_rms = residual / std::sqrt(static_cast<double>(factors.n_samples()));
  out.relative_error = residual.norm() / tau.norm();
  return out;
}

}  // namespace

std::string_view ToString(TorqueEstimator estimator) { return kTorqueEstimatorNames.Name(estimator); }

bool IsClosedLoopEstimator(TorqueEstimator estimator) {
  return estimator == TorqueEstimator::kInstrumentalVariables || estimator == TorqueEstimator::kDidim;
}

bool ParseTorqueEstimator(std::string_view text, TorqueEstimator* estimator, std::string* why) {
  return kTorqueEstimatorNames.Parse(text, estimator, why);
}

Eigen::MatrixXd StackBaseRegressor(const RobotModel& model, const FrictionModel& friction,
                                   const BaseParameters& base, const JointLog& log) {
  CheckLog(model, log);
  const int n = model.n_dof();
  Eigen::MatrixXd W(static_cast<Eigen::Index>(log.n_samples()) * n, base.n_base());
  RobotData data(model);
  Eigen::MatrixXd Y;
  Eigen::VectorXd q(n), qd(n), qdd(n);
  for (int s = 0; s < log.n_samples(); ++s) {
    q = log.q.row(s).transpose();
    qd = log.qd.row(s).transpose();
    qdd = log.qdd.row(s).transpose();
    ComputeJointTorqueRegressor(model, friction, q, qd, qdd, &data, &Y);
    for (int k = 0; k < base.n_base(); ++k) {
      W.block(static_cast<Eigen::Index>(s) * n, k, n, 1) = Y.col(base.independent[static_cast<size_t>(k)]);
    }
  }
  return W;
}

StackedFactors FactorStackedEquations(const RobotModel& model, const FrictionModel& friction,
                                      const BaseParameters& base, const JointLog& log, int n_threads) {
  CheckLog(model, log);
  const StackedFactors empty(base.n_base(), JointFactorColumns(model, friction, base));
  const int n_samples = log.n_samples();
  const int n_parts = std::max(1, (n_samples + kSamplesPerFactorPart - 1) / kSamplesPerFactorPart);
  if (n_threads <= 0) n_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  n_threads = std::min(n_threads, n_parts);
  // Part p (samples [p·P, (p + 1)·P)) is factored from zero by whichever
  // thread takes it next, each thread with its own workspace.
  std::vector<StackedFactors> parts(static_cast<size_t>(n_parts), empty);
  std::atomic<int> next_part{0};
  auto factor_parts = [&] {
    RobotData data(model);
    Eigen::MatrixXd Y;
    std::vector<Eigen::MatrixXd> rows(static_cast<size_t>(model.n_dof()));
    for (int p = next_part++; p < n_parts; p = next_part++) {
      const int s_begin = p * kSamplesPerFactorPart;
      const int s_end = std::min(n_samples, s_begin + kSamplesPerFactorPart);
      FactorSamples(model, friction, base, log, s_begin, s_end, &data, &Y, &rows,
                    &parts[static_cast<size_t>(p)]);
    }
  };
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto run = [&] {
    try {
      factor_parts();
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> threads;  // joined when the block ends, also on a throw
    for (int t = 1; t < n_threads; ++t) threads.emplace_back(run);
    run();
  }
  if (failure) std::rethrow_exception(failure);
  // Merge in part order.
  StackedFactors factors = std::move(parts.front());
  for (size_t p = 1; p < parts.size(); ++p) MergeStackedFactors(parts[p], &factors);
  return factors;
}

Eigen::VectorXd StackTorques(const JointLog& log) {
  // Row-major flattening of (n_samples × n_dof): sample by sample.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tau = log.tau;
  return Eigen::Map<const Eigen::VectorXd>(tau.data(), tau.size());
}

void StackEquations(const RobotModel& model, const FrictionModel& friction, const BaseParameters& base,
                    const JointLog& log, const std::optional<ParallelFilter>& filter, Eigen::MatrixXd* W,
                    Eigen::VectorXd* tau) {
  *W = StackBaseRegressor(model, friction, base, log);
  *tau = StackTorques(log);
  if (!filter) return;
  // [W τ] filtered per joint, the transients dropped, every k-th sample kept.
  Eigen::MatrixXd rows(W->rows(), W->cols() + 1);
  rows << *W, *tau;
  ParallelFilterStackedRows(filter->filter, filter->sample_rate_hz, model.n_dof(), &rows);
  *W = rows.leftCols(rows.cols() - 1);
  *tau = rows.col(rows.cols() - 1);
}

std::vector<Eigen::Index> StackedSamples(const JointLog& log, const std::optional<ParallelFilter>& filter) {
  if (filter) return ParallelFilterKeptSamples(filter->filter, filter->sample_rate_hz, log.n_samples());
  std::vector<Eigen::Index> all(static_cast<size_t>(log.n_samples()));
  for (size_t s = 0; s < all.size(); ++s) all[s] = static_cast<Eigen::Index>(s);
  return all;
}

bool PlausibilitySettings::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  // %g, not std::to_string's %f (1e300 would print 301 digits).
  auto g = [](double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", v);
    return std::string(text);
  };
  if (!(mass_factor_min >= 0.0) || !(mass_factor_max >= 1.0) || !(mass_factor_min <= 1.0) || !(mass_factor_max <= 1e6))
    return fail("plausibility.mass_factor_min, plausibility.mass_factor_max: expected 0 <= LO <= 1 <= HI <= 1e6 (factors of each link's robot-file mass), got " +
                g(mass_factor_min) + "," + g(mass_factor_max));
  if (!(total_mass >= 0.0) || !(total_mass <= 1e6))
    return fail("plausibility.total_mass: expected 0 (none) to 1e6 kg, got " + g(total_mass));
  if (!(total_mass_tolerance >= 0.0) || !(total_mass_tolerance <= 1.0))
    return fail("plausibility.total_mass_tolerance: expected a fraction in [0, 1], got " + g(total_mass_tolerance));
  if (!(prior_weight > 0.0) || !(prior_weight <= 1e6))
    return fail("plausibility.prior_weight: expected more than 0, up to 1e6, got " + g(prior_weight) +
                ": the prior decides what the log does not determine (with 0 that is arbitrary); for a negligible "
                "prior give a small value, e.g. 1e-8");
  if (!(cost_tolerance >= 0.0) || !(cost_tolerance <= 1e6))
    return fail("plausibility.cost_tolerance: expected a fraction from 0 to 1e6, got " + g(cost_tolerance));
  return true;
}

bool PlausibilitySettings::IsValidFor(const RobotModel& model, std::string* why) const {
  if (!IsValid(why)) return false;
  if (total_mass <= 0.0) return true;
  double file_total = 0.0;
  for (const Link& link : model.links()) file_total += link.inertia.mass;
  const double lo = total_mass * (1.0 - total_mass_tolerance), hi = total_mass * (1.0 + total_mass_tolerance);
  if (hi < mass_factor_min * file_total || lo > mass_factor_max * file_total) {
    char text[400];
    std::snprintf(text, sizeof(text),
                  "plausibility.total_mass %.6g kg (± %.3g %%) cannot be met: the links' bounds (plausibility.mass_factor_min, "
                  "plausibility.mass_factor_max %.3g,%.3g × the robot file's %.6g kg) allow %.6g to %.6g kg; widen "
                  "plausibility.mass_factor_min, plausibility.mass_factor_max or plausibility.total_mass_tolerance",
                  total_mass, 100.0 * total_mass_tolerance, mass_factor_min, mass_factor_max, file_total,
                  mass_factor_min * file_total, mass_factor_max * file_total);
    if (why) *why = text;
    return false;
  }
  return true;
}

PlausibleFitOptions MakePlausibleFitOptions(const RobotModel& model, const FrictionModel& friction,
                                            const PlausibilitySettings& settings) {
  const Eigen::VectorXd pi = StandardParameters(model, friction);
  const std::vector<std::string> names = StandardParameterNames(model, friction);
  PlausibleFitOptions options;
  options.prior_weight = settings.prior_weight;
  options.scale.resize(pi.size());
  for (int l = 0; l < model.n_links(); ++l) {
    const LinkInertia& inertia = model.link(l).inertia;
    const std::optional<Eigen::AlignedBox3d> box_B = LinkBoundingBox_B(model.link(l));
    // The link's size: half its box's diagonal, at least |c| and 5 cm.
    double length = std::max(0.05, inertia.p_BoBcm_B.norm());
    if (box_B) length = std::max(length, 0.5 * box_B->diagonal().norm());
    const int o = kInertialParametersPerLink * l;
    const double m = inertia.mass;
    options.scale[o] = m;
    options.scale.segment(o + 1, 3).setConstant(m * length);
    options.scale.segment(o + 4, 6).setConstant(m * length * length);
    LinkPlausibilityBounds bounds;
    bounds.mass_min = settings.mass_factor_min * m;
    bounds.mass_max = settings.mass_factor_max * m;
    const std::optional<CenterOfMassGeometryCheck> check = CheckCenterOfMassInGeometry(model.link(l));
    if (settings.com_in_geometry && check && check->contradicts()) {
      bounds.com_outside_geometry = check->distance;  // the box would contradict the file: no bound
    } else if (settings.com_in_geometry && box_B) {
      // Near the box (within the check's tolerance): grown to hold it, so the
      // bound never contradicts the file itself.
      const Eigen::AlignedBox3d box = Eigen::AlignedBox3d(*box_B).extend(inertia.p_BoBcm_B);
      bounds.bound_com = true;
      bounds.com_min_B = box.min();
      bounds.com_max_B = box.max();
    }
    options.links.push_back(bounds);
    options.link_names.push_back(model.link(l).name);
    options.joint_names.push_back(model.link(l).joint_name);
  }
  if (settings.total_mass > 0.0) {
    options.total_mass_min = settings.total_mass * (1.0 - settings.total_mass_tolerance);
    options.total_mass_max = settings.total_mass * (1.0 + settings.total_mass_tolerance);
  }
  // Friction and rotor inertia are physical only when >= 0 (offsets are signed).
  for (Eigen::Index k = kInertialParametersPerLink * model.n_links(); k < pi.size(); ++k) {
    options.scale[k] = std::max(std::abs(pi[k]), 1.0);
    const std::string& name = names[static_cast<size_t>(k)];
    if (name.rfind("Fv", 0) == 0 || name.rfind("Fc", 0) == 0 || name.rfind("Ia", 0) == 0)
      options.nonnegative.push_back(static_cast<int>(k));
  }
  return options;
}

const char* ToString(ModelVerdict verdict) {
  switch (verdict) {
    case ModelVerdict::kFitToLoad: return "fit to load";
    case ModelVerdict::kNotConverged: return "not converged";
    case ModelVerdict::kCostAboveOptimum: return "cost above the optimum";
  }
  return "?";
}

const char* ToKey(ModelVerdict verdict) {
  switch (verdict) {
    case ModelVerdict::kFitToLoad: return "fit_to_load";
    case ModelVerdict::kNotConverged: return "not_converged";
    case ModelVerdict::kCostAboveOptimum: return "cost_above_optimum";
  }
  return "?";
}

IdentificationVerdict JudgePlausibleFit(const PhysicallyConsistentFit& fit, double cost_tolerance) {
  IdentificationVerdict verdict;
  verdict.cost_tolerance = cost_tolerance;
  const double unit = std::max({fit.ols_cost, 1e-10 * fit.zero_cost, 1e-300});
  verdict.cost_excess = std::max(0.0, fit.cost - fit.ols_cost) / unit;
  // Converged: a feasible point whose duality gap certifies its objective
  // within kCertifiedGap of the optimum (the solver aims at 10⁻⁹ and may stop
  // just short of it where rounding ends the progress).
  const bool certified = fit.converged || (fit.feasible && std::isfinite(fit.duality_gap) && fit.duality_gap <= kCertifiedGap);
  verdict.status = !certified                             ? ModelVerdict::kNotConverged
                   : verdict.cost_excess > cost_tolerance ? ModelVerdict::kCostAboveOptimum
                                                          : ModelVerdict::kFitToLoad;
  char text[400];
  std::snprintf(text, sizeof(text), "%s: %s; cost %+.3g %% against the OLS optimum (tolerance %.3g %%)",
                ToString(verdict.status), fit.status.c_str(), 100.0 * verdict.cost_excess, 100.0 * cost_tolerance);
  verdict.message = text;
  if (verdict.fit_to_load()) return verdict;

  // The binding constraints by kind, each with the links it holds.
  std::string com_links, mass_links;
  bool total = false;
  for (const ActiveBound& b : fit.bounds_at_optimum) {
    const std::string name = b.text.substr(0, b.text.find(':'));
    if (b.quantity == ActiveBound::Quantity::kTotalMass) {
      total = true;
    } else if (b.quantity == ActiveBound::Quantity::kMass) {
      mass_links += (mass_links.empty() ? "" : ", ") + name;
    } else if (com_links.find(name) == std::string::npos) {
      com_links += (com_links.empty() ? "" : ", ") + name;
    }
  }
  std::string cause;
  if (verdict.status == ModelVerdict::kNotConverged)
    cause = "the solver stopped before certifying its optimum";
  if (!com_links.empty()) {
    cause += std::string(cause.empty() ? "" : "; ") + "the centre-of-mass bounds (the box around each link's shapes) " +
             "hold " + com_links + ": the file's shapes may not be placed in the frames of its inertials, or its " +
             "centres of mass are far from the robot's; fit without them (plausibility.com_in_geometry = false) or " +
             "correct the file's <visual>/<collision> or <inertial> origins";
  }
  if (!mass_links.empty()) {
    cause += std::string(cause.empty() ? "" : "; ") + "the mass bounds (plausibility.mass_factor_min, " +
             "plausibility.mass_factor_max × the file's) hold " + mass_links + ": the file's masses may be far " +
             "from the robot's, or the log's torques off in scale (drive gains, units, motor against joint side); " +
             "check the log, or widen the mass range if the file's masses are uncertain";
  }
  if (total) {
    cause += std::string(cause.empty() ? "" : "; ") + "the total mass (plausibility.total_mass ± " +
             "plausibility.total_mass_tolerance) holds the links: check it against the robot's";
  }
  if (cause.empty()) {
    cause = "no bound holds the fit, so the prior does: lower plausibility.prior_weight, or the data carry more "
            "than the model explains";
  }
  verdict.cause = cause;
  return verdict;
}

JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const JointLog& log,
                                              const JointTorqueOptions& options) {
  const BaseParameters base = ComputeBaseParameters(model, options.friction, options.base);
  // W held whole: for the IRLS passes and the scores at β̂.
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  const bool stacked = options.covariance == CovarianceMethod::kBatchMeans || options.estimator == TorqueEstimator::kIrls;
  if (stacked) StackEquations(model, options.friction, base, log, options.parallel_filter, &W, &tau);
  const ReweightedFold reweighted_fold = [&](const RobustRowWeights& weights, IrlsPassRecord* residuals) {
    return FactorStackedRows(W, tau, model.n_dof(), &weights, residuals);
  };
  JointTorqueIdentification out =
      IdentifyJointTorque(model, base, FactorEquations(model, options.friction, base, log, options.parallel_filter),
                          options, stacked ? &reweighted_fold : nullptr);
  if (options.covariance == CovarianceMethod::kBatchMeans) {
    // The scores at β̂: a second pass over the equations.
    ApplyStackedScoreCovariance(W, tau, model.n_dof(), &out.linear);
  }
  return out;
}

namespace {

// id->consistent and id->verdict from the combined factor [R z; 0 ρ] of the equations.
void SolveConsistentFit(const RobotModel& model, const Eigen::MatrixXd& factor, const JointTorqueOptions& options,
                        JointTorqueIdentification* id) {
  id->consistent = SolvePlausibleFit(factor, id->base, model.n_links(), StandardParameters(model, options.friction),
                                     MakePlausibleFitOptions(model, options.friction, options.plausibility));
  if (!std::isfinite(id->consistent.duality_gap) || !id->consistent.min_pseudo_inertia_eigenvalue.allFinite() ||
      id->consistent.status.rfind("infeasible", 0) == 0) {
    throw std::runtime_error("physically consistent estimate: " + id->consistent.status);
  }
  id->verdict = JudgePlausibleFit(id->consistent, options.plausibility.cost_tolerance);
}

}  // namespace

void CentreConsistentFit(const RobotModel& model, const StackedFactors& factors, const JointTorqueOptions& options,
                         const Eigen::VectorXd& beta_centre, JointTorqueIdentification* id) {
  Eigen::MatrixXd factor = CombinedFactor(factors, Eigen::VectorXd::Ones(model.n_dof()));
  const Eigen::Index p = factor.rows() - 1;
  if (beta_centre.size() != p) {
    throw std::invalid_argument("consistent fit: expected a centre of " + std::to_string(p) + " base parameters, got " +
                                std::to_string(beta_centre.size()));
  }
  // [R  R β_c; 0  ρ_c]: for every β, ‖R β − R β_c‖² + ρ_c², with ρ_c² = ‖R β_c − z‖² + ρ²
  // the residual the centre itself leaves (the cost at β = β_c).
  const Eigen::MatrixXd R = factor.topLeftCorner(p, p).triangularView<Eigen::Upper>();
  const double rho_c = std::hypot((R * beta_centre - factor.topRightCorner(p, 1)).norm(), factor(p, p));
  factor.topRightCorner(p, 1) = R * beta_centre;
  factor(p, p) = rho_c;
  SolveConsistentFit(model, factor, options, id);
}

JointTorqueIdentification IdentifyJointTorque(const RobotModel& model, const BaseParameters& base,
                                              const StackedFactors& factors, const JointTorqueOptions& options,
                                              const ReweightedFold* reweighted_fold) {
  JointTorqueIdentification out;
  out.base = base;
  if (factors.n_parameters != base.n_base() || factors.n_dof() != model.n_dof()) {
    throw std::invalid_argument("joint torque identification: expected factors of " + std::to_string(base.n_base()) +
                                " parameters and " + std::to_string(model.n_dof()) + " joints, got " +
                                std::to_string(factors.n_parameters) + " and " + std::to_string(factors.n_dof()));
  }
  CheckEnoughEquations(factors.n_samples(), model.n_dof(), base.n_base());
  out.standard_names = StandardParameterNames(model, options.friction);
  const Eigen::VectorXd pi_model = StandardParameters(model, options.friction);
  out.beta_model = out.base.combination * pi_model;
  switch (options.estimator) {
    case TorqueEstimator::kWls: out.linear = SolveWls(factors); break;
    case TorqueEstimator::kTls: out.linear = SolveTls(factors); break;
    case TorqueEstimator::kIrls:
      if (!reweighted_fold) {
        throw std::invalid_argument("estimator irls: needs passes over the equations, not only their folded factors");
      }
      out.linear = SolveIrls(factors, *reweighted_fold, options.irls);
      break;
    case TorqueEstimator::kOls:
    case TorqueEstimator::kPhysicallyConsistent:
    case TorqueEstimator::kInstrumentalVariables:  // their starting point (closed_loop_estimators.h)
    case TorqueEstimator::kDidim: out.linear = SolveOls(factors); break;
  }
  out.beta = out.linear.beta;
  // The plausible fit keeps the robot file's values in the directions the
  // log does not determine.
  SolveConsistentFit(model, CombinedFactor(factors, Eigen::VectorXd::Ones(model.n_dof())), options, &out);
  if (options.estimator == TorqueEstimator::kPhysicallyConsistent) out.beta = out.consistent.beta;
  out.fit = Predict(factors, out.beta);
  out.model_fit = Predict(factors, out.beta_model);
  return out;
}

TorquePrediction PredictTorques(const RobotModel& model, const JointTorqueOptions& options,
                                const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log) {
  return Predict(FactorEquations(model, options.friction, base, log, options.parallel_filter), beta);
}

TorquePrediction PredictTorques(const StackedFactors& factors, const Eigen::VectorXd& beta) {
  return Predict(factors, beta);
}

TorqueSeries PredictTorqueSeries(const RobotModel& model, const JointTorqueOptions& options,
                                 const BaseParameters& base, const Eigen::VectorXd& beta, const JointLog& log) {
  if (beta.size() != base.n_base()) {
    throw std::invalid_argument("torque prediction: expected " + std::to_string(base.n_base()) +
                                " base parameters, got " + std::to_string(beta.size()));
  }
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  StackEquations(model, options.friction, base, log, options.parallel_filter, &W, &tau);
  const std::vector<Eigen::Index> samples = StackedSamples(log, options.parallel_filter);
  const int n = model.n_dof();
  const Eigen::Index n_kept = static_cast<Eigen::Index>(samples.size());
  assert(W.rows() == n_kept * n);
  // The stacked rows are interleaved by joint (sample·n_dof + joint): row-major n_kept × n_dof.
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::VectorXd tau_hat = W * beta;
  TorqueSeries out;
  out.t.resize(n_kept);
  for (Eigen::Index k = 0; k < n_kept; ++k) out.t[k] = log.t[samples[static_cast<size_t>(k)]];
  out.measured = Eigen::Map<const RowMajor>(tau.data(), n_kept, n);
  out.predicted = Eigen::Map<const RowMajor>(tau_hat.data(), n_kept, n);
  return out;
}

}  // namespace idbench
