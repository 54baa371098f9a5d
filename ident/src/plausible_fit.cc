#include "idbench/ident/plausible_fit.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "plausible_program.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {
namespace {

// Entries of π within a link's 10: m, then h = m c (x, y, z).
constexpr int kMass = 0;
constexpr int kFirstMoment = 1;
constexpr double kPriorFloor = 1e-10;

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", v);
  return text;
}

// ‖W_b β − τ‖² = ‖R β − z‖² + ρ² from the factor [R z; 0 ρ] of [W_b τ].
double DataCost(const Eigen::MatrixXd& factor, const Eigen::VectorXd& beta) {
  const Eigen::Index p = beta.size();
  const double rho = factor(p, p);
  return (factor.topLeftCorner(p, p).triangularView<Eigen::Upper>() * beta - factor.col(p).head(p)).squaredNorm() +
         rho * rho;
}

// J(e_k): the pseudo-inertia of the k-th unit parameter vector of one link.
Eigen::Matrix4d UnitPseudoInertia(int k) {
  InertialParameters e = InertialParameters::Zero();
  e[k] = 1.0;
  return PseudoInertia(e);
}

// Bounds [lo, hi] on a mass, widened to 10⁻⁶ of hi around their middle
// where they are closer (a fixed mass): the barrier method needs an interior.
std::pair<double, double> WithInterior(double lo, double hi) {
  constexpr double kWidth = 1e-6;
  if (!std::isfinite(hi) || hi - lo >= kWidth * hi) return {lo, hi};
  const double middle = 0.5 * (lo + hi);
  return {middle - 0.5 * kWidth * hi, middle + 0.5 * kWidth * hi};
}

}  // namespace

bool PlausibleFitOptions::IsValid(int n_links, int n_standard, std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!links.empty() && static_cast<int>(links.size()) != n_links)
    return fail("expected bounds for " + std::to_string(n_links) + " links, got " + std::to_string(links.size()));
  for (size_t l = 0; l < links.size(); ++l) {
    const LinkPlausibilityBounds& b = links[l];
    const std::string where = "link " + std::to_string(l + 1) + ": ";
    if (!(b.mass_min >= 0.0) || !(b.mass_max >= b.mass_min) || std::isnan(b.mass_max))
      return fail(where + "mass bounds must satisfy 0 <= min <= max, got [" + Number(b.mass_min) + ", " + Number(b.mass_max) + "]");
    if (b.bound_com && (!b.com_min_B.allFinite() || !b.com_max_B.allFinite() || (b.com_max_B - b.com_min_B).minCoeff() < 0.0))
      return fail(where + "centre-of-mass box must be finite with min <= max");
  }
  if (!(total_mass_min >= 0.0) || !(total_mass_max >= total_mass_min) || std::isnan(total_mass_max))
    return fail("total mass bounds must satisfy 0 <= min <= max, got [" + Number(total_mass_min) + ", " + Number(total_mass_max) + "]");
  for (int k : nonnegative)
    if (k < kInertialParametersPerLink * n_links || k >= n_standard) return fail("nonnegative index " + std::to_string(k) + " is not a friction entry");
  if (scale.size() != n_standard || !scale.allFinite() || !(scale.minCoeff() > 0.0))
    return fail("expected " + std::to_string(n_standard) + " positive finite parameter scales");
  if (!(prior_weight >= 0.0) || !std::isfinite(prior_weight)) return fail("prior weight must be finite and >= 0");
  if (!(pseudo_inertia_margin >= 0.0) || !(pseudo_inertia_margin < 1.0)) return fail("pseudo-inertia margin must be in [0, 1)");
  if (!(gap_tolerance > 0.0) || max_iterations < 1) return fail("gap tolerance must be > 0 and iterations >= 1");
  if ((!link_names.empty() && static_cast<int>(link_names.size()) != n_links) ||
      (!joint_names.empty() && static_cast<int>(joint_names.size()) != n_links))
    return fail("expected " + std::to_string(n_links) + " link and joint names, got " + std::to_string(link_names.size()) +
                " and " + std::to_string(joint_names.size()));
  return true;
}

namespace internal {

PlausibleProgram MakePlausibleProgram(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                      const Eigen::VectorXd& pi_prior, const PlausibleFitOptions& options) {
  const Eigen::MatrixXd& C = base.combination;
  const Eigen::Index p = C.rows();
  const int n = static_cast<int>(C.cols());
  if (factor.rows() != p + 1 || factor.cols() != p + 1 || !factor.allFinite())
    throw std::invalid_argument("plausible fit: expected a finite " + std::to_string(p + 1) + "x" + std::to_string(p + 1) + " factor");
  if (n < kInertialParametersPerLink * n_links || pi_prior.size() != n || !pi_prior.allFinite())
    throw std::invalid_argument("plausible fit: expected a finite prior of " + std::to_string(n) + " parameters for " +
                                std::to_string(n_links) + " links");
  std::string why;
  if (!options.IsValid(n_links, n, &why)) throw std::invalid_argument("plausible fit: " + why);
  PlausibleProgram program;

  // Normalised least squares in x = D⁻¹(π − π_prior): the data rows
  // (R C D x − (z − R C π_prior))/s and the prior rows, with s² the cost of
  // the prior, so that the objective is O(1) whatever the robot's size.
  const Eigen::MatrixXd R = factor.topLeftCorner(p, p).triangularView<Eigen::Upper>();
  const Eigen::VectorXd z = factor.col(p).head(p);
  program.rho2 = factor(p, p) * factor(p, p);
  program.start_cost = DataCost(factor, C * pi_prior);
  program.zero_cost = z.squaredNorm() + program.rho2;
  // The unit: the prior's cost, at least 10⁻¹² of ‖τ‖² (= ‖z‖² + ρ²), so
  // that a noise-free log of the robot file itself keeps a sane scale.
  program.s2 = std::max({program.start_cost, 1e-12 * (z.squaredNorm() + program.rho2), 1e-300});
  const double s = std::sqrt(program.s2);
  // λ = γ ρ² / n, with ρ² floored so that noise-free data keep a prior term.
  const double lambda = options.prior_weight * std::max(program.rho2, 1e-12 * program.s2) / n;
  Eigen::MatrixXd M(p + n, n);
  M.topRows(p) = (R * C * options.scale.asDiagonal()) / s;
  // Prior weights λ_k = max(λ, κ ‖data column k‖²): where the data are 10⁵
  // times (in singular value) stronger than the prior, as on a nearly
  // noise-free log, the floor κ = 10⁻¹⁰ keeps the Newton systems within what
  // double precision resolves, at a relative bias of κ/(curvature) in the
  // directions the data determine.
  const Eigen::VectorXd data_curvature = M.topRows(p).colwise().squaredNorm().transpose();
  program.prior_weights = (kPriorFloor * data_curvature).cwiseMax(lambda / program.s2);
  // γ = 0 leaves a parameter no data reach without any weight (a zero column,
  // and D = scale/0): hold it at the prior with the floor of the strongest.
  const double empty_column_weight = kPriorFloor * std::max(data_curvature.maxCoeff(), 1e-300);
  for (Eigen::Index k = 0; k < n; ++k)
    if (!(program.prior_weights[k] > 0.0)) program.prior_weights[k] = empty_column_weight;
  M.bottomRows(n) = program.prior_weights.cwiseSqrt().asDiagonal();
  // Variables u = x ∘ ‖M_k‖ (unit-norm columns): the same problem, better
  // conditioned. π = π_prior + D ∘ u, D the scale over the column norms.
  program.column_norms = M.colwise().norm().transpose();
  program.D = options.scale.cwiseQuotient(program.column_norms);
  const Eigen::VectorXd& D = program.D;
  M = M * program.column_norms.cwiseInverse().asDiagonal();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(p + n);
  rhs.head(p) = (z - R * (C * pi_prior)) / s;
  // QR to n rows: ‖M u − rhs‖² = ‖R1 u − z1‖² + rest.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(M);
  program.sdp.R = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
  const Eigen::VectorXd qt_rhs = qr.householderQ().transpose() * rhs;
  program.sdp.z = qt_rhs.head(n);
  program.rest = qt_rhs.tail(p).squaredNorm();

  // Per link: J(π_prior + D u) − ε diag(D_I, D_I, D_I, D_m) ⪰ 0, J linear in π.
  for (int l = 0; l < n_links; ++l) {
    const int o = kInertialParametersPerLink * l;
    const double inertia_scale = options.scale.segment(o + 4, 6).maxCoeff();
    const Eigen::Vector4d margin(inertia_scale, inertia_scale, inertia_scale, options.scale[o + kMass]);
    LmiBlock block;
    block.C = PseudoInertia(pi_prior.segment(o, kInertialParametersPerLink)) - Eigen::Matrix4d(options.pseudo_inertia_margin * margin.asDiagonal());
    for (int k = 0; k < kInertialParametersPerLink; ++k) {
      block.variables.push_back(o + k);
      block.B.push_back(D[o + k] * UnitPseudoInertia(k));
    }
    program.sdp.blocks.push_back(std::move(block));
  }
  // Linear rows c + aᵀu ≥ 0. The mass of link l is m_prior + D_m u_m.
  auto add_row = [&](double c, std::vector<std::pair<int, double>> a) {
    program.sdp.rows.push_back(LinearInequality{c, std::move(a)});
  };
  auto mass_term = [&](int l, double factor_of_mass) {
    return std::make_pair(kInertialParametersPerLink * l + kMass, factor_of_mass * D[kInertialParametersPerLink * l + kMass]);
  };
  for (size_t l = 0; l < options.links.size(); ++l) {
    const LinkPlausibilityBounds& bounds = options.links[l];
    const int o = kInertialParametersPerLink * static_cast<int>(l);
    const double m0 = pi_prior[o + kMass];
    const auto [mass_min, mass_max] = WithInterior(bounds.mass_min, bounds.mass_max);
    if (std::isfinite(mass_max)) add_row(mass_max - m0, {mass_term(static_cast<int>(l), -1.0)});
    if (mass_min > 0.0) add_row(m0 - mass_min, {mass_term(static_cast<int>(l), 1.0)});
    if (!bounds.bound_com) continue;
    // m c_min ≤ h ≤ m c_max, h = h_prior + D_h u_h.
    for (int a = 0; a < 3; ++a) {
      const int h = o + kFirstMoment + a;
      const double h0 = pi_prior[h];
      add_row(h0 - bounds.com_min_B[a] * m0, {{h, D[h]}, mass_term(static_cast<int>(l), -bounds.com_min_B[a])});
      add_row(bounds.com_max_B[a] * m0 - h0, {{h, -D[h]}, mass_term(static_cast<int>(l), bounds.com_max_B[a])});
    }
  }
  double total0 = 0.0;
  std::vector<std::pair<int, double>> total_up, total_down;
  for (int l = 0; l < n_links; ++l) {
    total0 += pi_prior[kInertialParametersPerLink * l + kMass];
    total_up.push_back(mass_term(l, -1.0));
    total_down.push_back(mass_term(l, 1.0));
  }
  const auto [total_min, total_max] = WithInterior(options.total_mass_min, options.total_mass_max);
  if (std::isfinite(total_max)) add_row(total_max - total0, total_up);
  if (total_min > 0.0) add_row(total0 - total_min, total_down);
  for (int k : options.nonnegative) add_row(pi_prior[k], {{k, D[k]}});

  // Start at the prior with the nonnegative terms raised off zero (a robot
  // file without friction would start on the boundary).
  program.start = Eigen::VectorXd::Zero(n);
  for (int k : options.nonnegative) {
    const double floor = 1e-3 * options.scale[k];
    if (pi_prior[k] < floor) program.start[k] = (floor - pi_prior[k]) / D[k];
  }
  return program;
}

}  // namespace internal

PhysicallyConsistentFit SolvePlausibleFit(const Eigen::MatrixXd& factor, const BaseParameters& base, int n_links,
                                          const Eigen::VectorXd& pi_prior, const PlausibleFitOptions& options) {
  const internal::PlausibleProgram program = internal::MakePlausibleProgram(factor, base, n_links, pi_prior, options);
  internal::QuadraticSdpOptions solver;
  solver.relative_gap = options.gap_tolerance;
  solver.objective_offset = program.rest + program.rho2 / program.s2;
  // Costs below 10⁻¹² of ‖τ‖² count as zero (a residual torque 10⁻⁶ of the
  // measured one, which double precision no longer resolves in the factor's
  // cost): a noise-free log whose OLS optimum sits a rounding error outside a
  // bound has its gap measured against that, as the payload fit does.
  solver.objective_floor = std::max(1e-12, 1e-12 * program.zero_cost / program.s2);
  solver.max_newton_steps = options.max_iterations;
  solver.start = program.start;
  const internal::QuadraticSdpSolution solution = internal::SolveQuadraticSdp(program.sdp, solver);
  Eigen::VectorXd u = solution.u;
  // The standard parameters no base parameter contains appear only in the
  // prior term: at the optimum they equal the prior unless a constraint holds
  // them. The barrier method leaves them within its tolerance, which the
  // prior's small weight turns into visible drift; put each link's back
  // where that keeps the point strictly feasible (the objective can only fall).
  for (int l = 0; l < n_links; ++l) {
    Eigen::VectorXd snapped = u;
    for (int k : base.unexcited)
      if (k / kInertialParametersPerLink == l) snapped[k] = 0.0;
    if (snapped != u && internal::IsStrictlyFeasible(program.sdp, snapped)) u = snapped;
  }
  for (int k : base.unexcited) {  // friction terms no data reach
    if (k < kInertialParametersPerLink * n_links) continue;
    Eigen::VectorXd snapped = u;
    snapped[k] = program.start[k];
    if (internal::IsStrictlyFeasible(program.sdp, snapped)) u = snapped;
  }

  PhysicallyConsistentFit fit;
  fit.pi = pi_prior + program.D.cwiseProduct(u);
  fit.beta = base.combination * fit.pi;
  fit.cost = DataCost(factor, fit.beta);
  fit.ols_cost = program.rho2;
  fit.start_cost = program.start_cost;
  fit.prior_cost = program.s2 * program.prior_weights.dot(u.cwiseQuotient(program.column_norms).cwiseAbs2());
  fit.min_pseudo_inertia_eigenvalue = MinPseudoInertiaEigenvalues(fit.pi, n_links);
  fit.evaluations = solution.newton_steps;
  fit.duality_gap = solution.relative_gap;
  fit.converged = solution.converged;
  fit.feasible = solution.feasible;
  char status[200];
  std::snprintf(status, sizeof(status), "%s: relative duality gap %.2g", solution.status.c_str(), fit.duality_gap);
  fit.status = solution.feasible ? status : solution.status;

  // The bounds the optimum lies on (within 1e-6 of the scale), by link name.
  fit.zero_cost = program.zero_cost;
  auto link_name = [&](int l) {
    std::string name = l < static_cast<int>(options.link_names.size()) ? "link '" + options.link_names[static_cast<size_t>(l)] + "'"
                                                                        : "link " + std::to_string(l + 1);
    if (l < static_cast<int>(options.joint_names.size())) name += " (joint '" + options.joint_names[static_cast<size_t>(l)] + "')";
    return name;
  };
  auto add_bound = [&](ActiveBound::Quantity quantity, int l, bool upper, double bound, double file_value) {
    ActiveBound b{quantity, l, upper, bound, file_value, ""};
    const char* side = upper ? "upper" : "lower";
    if (quantity == ActiveBound::Quantity::kMass || quantity == ActiveBound::Quantity::kTotalMass) {
      b.text = (l >= 0 ? link_name(l) + ": mass" : std::string("total mass of the moving links")) + " at its " + side +
               " bound " + Number(bound) + " kg (" + Number(bound / file_value) + " × the file's " + Number(file_value) + " kg)";
    } else {
      const char axis = static_cast<char>('x' + (static_cast<int>(quantity) - static_cast<int>(ActiveBound::Quantity::kComX)));
      b.text = link_name(l) + ": centre of mass " + axis + " on the " + side + " face of the box around its shapes, " +
               Number(bound) + " m (the file's: " + Number(file_value) + " m)";
    }
    fit.active_bounds.push_back(b.text);
    fit.bounds_at_optimum.push_back(std::move(b));
  };
  double total = 0.0, total_file = 0.0;
  for (int l = 0; l < n_links; ++l) {
    total += fit.pi[kInertialParametersPerLink * l + kMass];
    total_file += pi_prior[kInertialParametersPerLink * l + kMass];
  }
  for (size_t l = 0; l < options.links.size(); ++l) {
    const LinkPlausibilityBounds& bounds = options.links[l];
    const int li = static_cast<int>(l);
    const int o = kInertialParametersPerLink * li;
    const double m = fit.pi[o + kMass], m0 = pi_prior[o + kMass];
    const double tolerance = 1e-6 * options.scale[o + kMass];
    if (std::isfinite(bounds.mass_max) && m >= bounds.mass_max - tolerance)
      add_bound(ActiveBound::Quantity::kMass, li, true, bounds.mass_max, m0);
    else if (bounds.mass_min > 0.0 && m <= bounds.mass_min + tolerance)  // one of two that meet
      add_bound(ActiveBound::Quantity::kMass, li, false, bounds.mass_min, m0);
    if (!bounds.bound_com || !(m > 0.0)) continue;
    for (int a = 0; a < 3; ++a) {
      const double c = fit.pi[o + kFirstMoment + a] / m, c0 = pi_prior[o + kFirstMoment + a] / m0;
      const double length_tolerance = 1e-6 * options.scale[o + kFirstMoment + a] / options.scale[o + kMass];
      const auto quantity = static_cast<ActiveBound::Quantity>(static_cast<int>(ActiveBound::Quantity::kComX) + a);
      if (c <= bounds.com_min_B[a] + length_tolerance) add_bound(quantity, li, false, bounds.com_min_B[a], c0);
      if (c >= bounds.com_max_B[a] - length_tolerance) add_bound(quantity, li, true, bounds.com_max_B[a], c0);
    }
  }
  const double total_tolerance = 1e-6 * std::max(total_file, 1e-300);
  if (std::isfinite(options.total_mass_max) && total >= options.total_mass_max - total_tolerance)
    add_bound(ActiveBound::Quantity::kTotalMass, -1, true, options.total_mass_max, total_file);
  else if (options.total_mass_min > 0.0 && total <= options.total_mass_min + total_tolerance)
    add_bound(ActiveBound::Quantity::kTotalMass, -1, false, options.total_mass_min, total_file);
  return fit;
}

}  // namespace idbench
