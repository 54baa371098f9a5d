#include "idbench/excitation/excitation_design.h"

#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/resource_limits.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/home_pose.h"
#include "idbench/ident/least_squares.h"

namespace idbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFeasibilityTolerance = 1e-9;  // of a normalised constraint
// SLSQP takes the grid rows within this fraction of their limit's scale
// (joint range, velocity or acceleration limit) of being active.
constexpr double kNearActive = 0.3;

std::string Format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

// One start of the optimizer: NLopt callbacks and the best feasible point.
struct StartRun {
  const DesignProblem* problem = nullptr;
  const DesignOptions* options = nullptr;
  const DesignControl* control = nullptr;
  int index = 0;
  std::optional<DesignProblem::Workspace> ws;
  nlopt_opt opt = nullptr;
  int evaluations = 0;
  int feasible_at = -1;  // see DesignStartSummary
  double best_value = kInf;
  Eigen::VectorXd best_theta;
  Eigen::VectorXd start_theta, last_theta;  // the start point; where the search ended
  std::vector<double> nonlinear_values;

  Eigen::VectorXd pending_theta;  // see Objective
  double pending_value = kInf;

  // SLSQP's linear rows: those within kNearActive of their limit at the
  // points it was (re)started from. Its quadratic subproblem costs in
  // proportion to the rows, and most grid rows are far from any limit.
  // When SLSQP steps outside a row it did not take, the run stops there
  // (reselect) and resumes with the rows near that point added.
  std::vector<int> rows;
  std::vector<char> taken;  // per grid row
  bool reselect = false;
  Eigen::VectorXd reselect_theta;  // where it stepped outside

  // The rows near theta, and near also (when given) the other point.
  // keep: also the rows already taken (a resume within one Optimize, so that
  // two points outside different rows cannot alternate forever).
  void SelectRows(const double* theta, const double* also = nullptr, bool keep = false) {
    if (options->algorithm != DesignAlgorithm::kSlsqp) return;
    const std::vector<LinearRow>& all = problem->rows();
    if (!keep || taken.size() != all.size()) taken.assign(all.size(), 0);
    rows.clear();
    for (size_t i = 0; i < all.size(); ++i) {
      if (taken[i] || problem->LinearValue(all[i], theta) > -kNearActive ||
          (also && problem->LinearValue(all[i], also) > -kNearActive)) {
        taken[i] = 1;
        rows.push_back(static_cast<int>(i));
      }
    }
  }

  bool ViolatesUntakenRow(const double* theta) const {
    const std::vector<LinearRow>& all = problem->rows();
    for (size_t i = 0; i < all.size(); ++i) {
      if (!taken[i] && problem->LinearValue(all[i], theta) > kFeasibilityTolerance) return true;
    }
    return false;
  }

  // Whether another Optimize may follow (each has its own evaluation budget).
  static bool Resumable(nlopt_result result) { return result != NLOPT_FORCED_STOP && result != NLOPT_MAXTIME_REACHED; }

  // Runs the optimizer from *theta (left at its last point) for at most
  // max_evaluations; SLSQP resumes with more rows while its result violates
  // rows it did not take.
  nlopt_result Optimize(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                        std::chrono::steady_clock::time_point t_begin, Eigen::VectorXd* theta);

  // Evaluates the nonlinear constraints into nonlinear_values.
  bool NonlinearFeasible(const double* theta) {
    nonlinear_values.resize(static_cast<size_t>(problem->n_nonlinear_constraints()));
    if (nonlinear_values.empty()) return true;
    problem->NonlinearConstraints(theta, nonlinear_values.data(), nullptr, &*ws);
    return *std::max_element(nonlinear_values.begin(), nonlinear_values.end()) <= kFeasibilityTolerance;
  }

  // The worst normalised violation of every constraint at theta (≤ 0: feasible).
  double Violation(const double* theta) {
    double v = problem->MaxLinearViolation(theta);
    NonlinearFeasible(theta);
    for (double c : nonlinear_values) v = std::max(v, c);
    return v;
  }

  bool Feasible(const double* theta) {
    return problem->MaxLinearViolation(theta) <= kFeasibilityTolerance && NonlinearFeasible(theta);
  }

  // Penalty for the unconstrained (SBPLX) form: squared normalised violations,
  // the nonlinear ones from *nonlinear_values (already evaluated at theta).
  double Penalty(const double* theta) const {
    double p = 0.0;
    for (const LinearRow& row : problem->rows()) {
      const double v = problem->LinearValue(row, theta);
      if (v > 0.0) p += v * v;
    }
    for (double v : nonlinear_values) p += v > 0.0 ? v * v : 0.0;
    return 1e4 * p;
  }

  void Consider(const double* theta, double value) {
    if (feasible_at < 0) feasible_at = evaluations;
    if (value >= best_value) return;
    best_value = value;
    best_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
  }

  // The criterion, and the best feasible point so far. When NLopt evaluates
  // the nonlinear constraints itself (right after the objective, at the same
  // x), a point that meets the linear rows waits for them (pending) rather
  // than computing them twice.
  double Objective(const double* theta, double* grad) {
    ++evaluations;
    if (control->stop && control->stop->load()) nlopt_force_stop(opt);
    const double c = problem->Criterion(theta, grad, &*ws);
    const bool linear_ok = problem->MaxLinearViolation(theta) <= kFeasibilityTolerance;
    if (!linear_ok && !taken.empty() && ViolatesUntakenRow(theta)) {
      reselect = true;
      reselect_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
      nlopt_force_stop(opt);
    }
    const bool sbplx = options->algorithm == DesignAlgorithm::kSbplx;
    pending_theta.resize(0);
    bool feasible = linear_ok;
    if (problem->n_nonlinear_constraints() > 0 && sbplx) {
      feasible = linear_ok && NonlinearFeasible(theta);
    } else if (problem->n_nonlinear_constraints() > 0) {
      feasible = false;
      if (linear_ok && c < best_value) {
        pending_theta = Eigen::Map<const Eigen::VectorXd>(theta, problem->n_unknowns());
        pending_value = c;
      }
    }
    if (feasible) Consider(theta, c);
    if (control->progress && evaluations % 20 == 0) control->progress({index, evaluations, best_value, linear_ok});
    return sbplx ? c + Penalty(theta) : c;
  }

  static double NloptObjective(unsigned, const double* x, double* grad, void* data) {
    return static_cast<StartRun*>(data)->Objective(x, grad);
  }

  // The selected grid rows (SLSQP).
  static void NloptLinear(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    const auto* self = static_cast<StartRun*>(data);
    const DesignProblem& p = *self->problem;
    if (grad) std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
    for (unsigned i = 0; i < m; ++i) {
      const LinearRow& row = p.rows()[static_cast<size_t>(self->rows[i])];
      result[i] = p.LinearValue(row, x);
      if (grad) {
        std::copy(row.coefficients.data(), row.coefficients.data() + p.block(),
                  grad + static_cast<size_t>(i) * n + static_cast<size_t>(row.joint * p.block()));
      }
    }
  }

  // One constraint per joint × quantity: the worst grid row (COBYLA, MMA),
  // with that row's gradient.
  static void NloptGrouped(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    const auto* self = static_cast<StartRun*>(data);
    const DesignProblem& p = *self->problem;
    std::fill(result, result + m, -kInf);
    std::vector<const LinearRow*> worst(m, nullptr);
    for (const LinearRow& row : p.rows()) {
      const double v = p.LinearValue(row, x);
      if (v > result[row.group]) result[row.group] = v, worst[static_cast<size_t>(row.group)] = &row;
    }
    if (!grad) return;
    std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
    for (unsigned i = 0; i < m; ++i) {
      if (const LinearRow* row = worst[i]) {
        std::copy(row->coefficients.data(), row->coefficients.data() + p.block(),
                  grad + static_cast<size_t>(i) * n + static_cast<size_t>(row->joint * p.block()));
      } else {
        result[i] = -1.0;  // a joint without position limits
      }
    }
  }

  static void NloptNonlinear(unsigned m, double* result, unsigned, const double* x, double* grad, void* data) {
    auto* self = static_cast<StartRun*>(data);
    self->problem->NonlinearConstraints(x, result, grad, &*self->ws);
    const Eigen::VectorXd& p = self->pending_theta;
    if (p.size() > 0 && std::equal(p.data(), p.data() + p.size(), x) &&
        *std::max_element(result, result + m) <= kFeasibilityTolerance) {
      self->Consider(x, self->pending_value);
    }
    self->pending_theta.resize(0);
  }
};

nlopt_result StartRun::Optimize(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                std::chrono::steady_clock::time_point t_begin, Eigen::VectorXd* theta) {
  const nlopt_algorithm algorithm = options->algorithm == DesignAlgorithm::kSlsqp    ? NLOPT_LD_SLSQP
                                    : options->algorithm == DesignAlgorithm::kMma    ? NLOPT_LD_MMA
                                    : options->algorithm == DesignAlgorithm::kCobyla ? NLOPT_LN_COBYLA
                                                                                     : NLOPT_LN_SBPLX;
  const unsigned n_theta = static_cast<unsigned>(problem->n_unknowns());
  nlopt_result result = NLOPT_SUCCESS;
  const int first_evaluation = evaluations;
  for (;;) {
    opt = nlopt_create(algorithm, n_theta);
    nlopt_set_min_objective(opt, &StartRun::NloptObjective, this);
    nlopt_set_lower_bounds(opt, lower.data());
    nlopt_set_upper_bounds(opt, upper.data());
    // SLSQP with one max-row per limit stalls (cond 170 where the rows reach
    // 42 for puma560); MMA's dual is too slow with many rows, so it and
    // COBYLA take the max.
    if (algorithm == NLOPT_LD_SLSQP) {
      const std::vector<double> tol(rows.size(), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptLinear, this,
                                       tol.data());
    } else if (algorithm != NLOPT_LN_SBPLX) {
      const std::vector<double> tol(static_cast<size_t>(problem->n_groups()), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptGrouped, this,
                                       tol.data());
    }
    if (problem->n_nonlinear_constraints() > 0 && algorithm != NLOPT_LN_SBPLX) {
      const std::vector<double> tol(static_cast<size_t>(problem->n_nonlinear_constraints()), 1e-10);
      nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(tol.size()), &StartRun::NloptNonlinear, this,
                                       tol.data());
    }
    if (algorithm == NLOPT_LN_COBYLA || algorithm == NLOPT_LN_SBPLX) {
      // A first step of 10 % of each unknown's box (COBYLA's and SBPLX's scale).
      const Eigen::VectorXd step = 0.1 * (upper - lower).cwiseMin(2.0 * theta->cwiseAbs().cwiseMax(1e-2));
      nlopt_set_initial_step(opt, step.data());
    }
    nlopt_set_maxeval(opt, std::max(1, options->max_evaluations - (evaluations - first_evaluation)));
    nlopt_set_ftol_rel(opt, 1e-10);  // looser (1e-7) stops SLSQP on plateaus: cond 50 instead of 43
    nlopt_set_xtol_rel(opt, 1e-10);
    if (options->max_seconds > 0.0) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
      nlopt_set_maxtime(opt, std::max(1e-3, options->max_seconds - elapsed));
    }
    double value = 0.0;
    reselect = false;
    result = nlopt_optimize(opt, theta->data(), &value);
    nlopt_destroy(opt);
    opt = nullptr;
    if (!reselect || (control->stop && control->stop->load()) ||
        evaluations - first_evaluation >= options->max_evaluations) {
      break;
    }
    // Resume from the best feasible point (else where it stepped out) with
    // the rows near both.
    if (best_theta.size() > 0) *theta = best_theta;
    else *theta = reselect_theta;
    SelectRows(theta->data(), reselect_theta.data(), true);
  }
  if (reselect && result == NLOPT_FORCED_STOP && !(control->stop && control->stop->load())) {
    result = NLOPT_MAXEVAL_REACHED;  // stopped to resume, but out of evaluations
  }
  return result;
}

}  // namespace

std::vector<std::string> DesignAlgorithmNames() { return {"slsqp", "mma", "cobyla", "sbplx"}; }
std::string DesignAlgorithmName(DesignAlgorithm algorithm) {
  return DesignAlgorithmNames()[static_cast<size_t>(algorithm)];
}
std::optional<DesignAlgorithm> ParseDesignAlgorithm(const std::string& name) {
  return EnumFromName<DesignAlgorithm>(DesignAlgorithmNames(), name);
}

bool DesignOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (harmonics < 1 || harmonics > FourierSeriesTrajectory::kMaxHarmonics) {
    return fail("--harmonics must be in 1.." + std::to_string(FourierSeriesTrajectory::kMaxHarmonics) + ", got " +
                std::to_string(harmonics));
  }
  if (!(f0 > 0.0) || !(f0 <= 100.0)) return fail(Format("--f0 must be in (0, 100] Hz, got %g", f0));
  if (!(duration >= 0.0) || !std::isfinite(duration)) return fail(Format("--duration must be >= 0 s, got %g", duration));
  const double top = f0 * harmonics * period_duration();  // periods of the top harmonic
  if (samples < 8 * top) {
    return fail(Format("--samples must be at least %g (8 per period of the highest harmonic, %g Hz), got %g",
                       std::ceil(8 * top), f0 * harmonics, samples));
  }
  if (starts < 1) return fail("--starts must be >= 1, got " + std::to_string(starts));
  if (threads < 1 || threads > MaxThreads()) {
    return fail("--threads must be in 1.." + std::to_string(MaxThreads()) + " (4 per hardware thread), got " +
                std::to_string(threads));
  }
  if (max_evaluations < 1) return fail("--max-evaluations must be >= 1");
  if (!(max_seconds >= 0.0)) return fail("--max-time must be >= 0");
  if (!(margin >= 0.0 && margin < 0.5)) return fail(Format("--margin must be in [0, 0.5), got %g", margin));
  if (!std::isfinite(clearance) || clearance > 1.0) return fail(Format("--clearance must be at most 1 m, got %g", clearance));
  if (!(check_rate_hz > 0.0)) return fail("the check rate must be > 0 Hz");
  if (!(ramp_seconds >= 0.0 && ramp_seconds <= kMaxRampSeconds)) {
    return fail(Format("--ramp must be in [0, %g] s, got ", kMaxRampSeconds) + Format("%g", ramp_seconds));
  }
  return true;
}

// A start's outcome line and whether it got anywhere (DesignStartSummary).
static void DescribeProgress(DesignStartSummary* s) {
  // A criterion change below this (relative) is no change.
  constexpr double kUnchanged = 1e-9;
  if (std::isfinite(s->best_value)) {
    const bool from_infeasible = s->initial_violation > kFeasibilityTolerance;
    const bool improved = s->best_value < s->initial_value - kUnchanged * std::max(1.0, std::abs(s->initial_value));
    s->progressed = improved || from_infeasible;
    s->outcome = improved          ? "improved"
                 : from_infeasible ? "reached the limits from an infeasible start"
                                   : "no progress: the criterion did not improve on the start point";
    return;
  }
  s->progressed = s->final_violation < s->initial_violation - kFeasibilityTolerance;
  s->outcome = (s->progressed ? "infeasible: the violation fell from " : "no progress: infeasible, the violation went from ") +
               Format("%.3g to %.3g", s->initial_violation, s->final_violation) + " (of a limit's scale)";
}

std::string DesignResult::Rejection() const {
  if (!check.feasible()) return "the design violates the limits or the clearance at " + Format("%g Hz", check.rate_hz);
  const bool improved = value < initial_value - 1e-9 * std::max(1.0, std::abs(initial_value));
  if (!improved) {
    int none = 0;
    for (const DesignStartSummary& s : starts) none += s.progressed ? 0 : 1;
    return "no progress: the design is its start point (criterion unchanged); " + std::to_string(none) + " of " +
           std::to_string(starts.size()) + " starts made no progress";
  }
  return "";
}

RampedTrajectory DesignResult::RobotTrajectory() const {
  return RampedTrajectory(std::make_shared<FourierSeriesTrajectory>(trajectory), home, ramp_seconds);
}

std::vector<double> DesignSampleTimes(const DesignOptions& options) {
  const double T = options.period_duration();
  const int N = options.samples;
  std::vector<double> times(static_cast<size_t>(N));
  // A periodic motion is sampled on [0, T) (T repeats 0); rest-to-rest on [0, T].
  const double dt = options.rest_to_rest ? T / (N - 1) : T / N;
  for (int k = 0; k < N; ++k) times[static_cast<size_t>(k)] = k * dt;
  return times;
}

void CheckDesignLimits(const RobotModel& model, const std::vector<JointLimits>& limits) {
  if (static_cast<int>(limits.size()) != model.n_dof()) {
    throw std::invalid_argument("limits: expected " + std::to_string(model.n_dof()) + " joints, got " +
                                std::to_string(limits.size()));
  }
  for (int j = 0; j < model.n_dof(); ++j) {
    const JointLimits& l = limits[static_cast<size_t>(j)];
    const std::string who = "joint " + std::to_string(j + 1) + " ('" + model.link(j).joint_name + "')";
    if (!(l.qd_max > 0.0) || !std::isfinite(l.qd_max)) {
      throw std::invalid_argument(who + ": the velocity limit qd_max must be finite and > 0, got " +
                                  Format("%g", l.qd_max) + " (give it in --limits)");
    }
    if (!(l.qdd_max > 0.0) || !std::isfinite(l.qdd_max)) {
      throw std::invalid_argument(who + ": the acceleration limit qdd_max must be finite and > 0, got " +
                                  Format("%g", l.qdd_max) + " (give it in --limits)");
    }
    if (!(l.q_min < l.q_max)) {
      throw std::invalid_argument(who + Format(": q_min = %g must be below q_max = %g rad", l.q_min, l.q_max));
    }
    if (!(l.tau_max > 0.0)) throw std::invalid_argument(who + Format(": tau_max must be > 0, got %g", l.tau_max));
  }
}

bool FeasibilityCheck::feasible() const {
  return std::all_of(margins.begin(), margins.end(), [](const ConstraintMargin& m) { return m.margin >= 0.0; });
}

std::string FeasibilityCheck::Explain() const {
  std::string out;
  for (const ConstraintMargin& m : margins) {
    if (m.margin >= 0.0) continue;
    if (m.quantity == "clearance") {
      out += m.pair + Format(" clearance: %.4g m at t = %.4g s is below its minimum %.4g m", m.value, m.time, m.limit) +
             (m.held_at_home ? " (its distance at q = 0, closer than the clearance asked)" : "") +
             Format(" by %.3g m\n", -m.margin);
      continue;
    }
    const char* unit = m.quantity == "qd" ? "rad/s" : m.quantity == "qdd" ? "rad/s²" : m.quantity == "tau" ? "N m" : "rad";
    const bool lower = m.quantity == "q_min";
    out += "joint " + std::to_string(m.joint + 1) + " " + m.quantity + ": " +
           (m.quantity == "q_min" || m.quantity == "q_max" ? "q" : "|" + m.quantity + "|") +
           Format(" = %.6g", m.value) + " " + unit + Format(" at t = %.4g s ", m.time) +
           (lower ? "is below" : "exceeds") + Format(" the limit %.6g ", m.limit) + unit +
           Format(" by %.3g ", -m.margin) + unit + "\n";
  }
  return out;
}

FeasibilityCheck CheckTrajectoryLimits(const RobotModel& model, const std::vector<JointLimits>& limits,
                                       const Trajectory& trajectory, double rate_hz, const ClearanceModel* clearance) {
  const int n = model.n_dof();
  FeasibilityCheck check;
  check.rate_hz = rate_hz;
  const char* names[5] = {"q_min", "q_max", "qd", "qdd", "tau"};
  auto limit_of = [&](int j, int i) {
    const JointLimits& l = limits[static_cast<size_t>(j)];
    const double values[5] = {l.q_min, l.q_max, l.qd_max, l.qdd_max, l.tau_max};
    return values[i];
  };
  std::vector<ConstraintMargin> worst;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < 5; ++i) {
      ConstraintMargin m;
      m.quantity = names[i];
      m.joint = j;
      m.limit = limit_of(j, i);
      m.margin = kInf;
      worst.push_back(m);
    }
  }
  const size_t n_pairs = clearance ? clearance->pairs().size() : 0;
  for (size_t i = 0; i < n_pairs; ++i) {
    ConstraintMargin m;
    m.quantity = "clearance";
    m.joint = static_cast<int>(i);
    m.pair = clearance->pairs()[i].Name(model);
    m.limit = clearance->pairs()[i].minimum;
    m.held_at_home = m.limit < clearance->min_clearance();
    m.value = kInf;  // the closest distance so far
    m.margin = kInf;
    worst.push_back(m);
  }
  std::vector<Clearance> distances;
  std::vector<double> closest(n_pairs);
  RobotData data(model);
  JointState x(n);
  const long steps = static_cast<long>(std::floor(trajectory.duration() * rate_hz + 1e-9));
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    trajectory.Evaluate(t, &x);
    Eigen::VectorXd tau = InverseDynamics(model, x.q, x.qd, x.qdd, &data);
    AddJointDynamicsTorque(model, x.qd, x.qdd, &tau);
    for (int j = 0; j < n; ++j) {
      const double values[5] = {x.q[j], x.q[j], std::abs(x.qd[j]), std::abs(x.qdd[j]), std::abs(tau[j])};
      for (int i = 0; i < 5; ++i) {
        ConstraintMargin& w = worst[static_cast<size_t>(5 * j + i)];
        const double margin = i == 0 ? values[i] - w.limit : w.limit - values[i];
        if (margin < w.margin) w.margin = margin, w.time = t, w.value = values[i];
      }
    }
    if (n_pairs == 0) continue;
    for (size_t i = 0; i < n_pairs; ++i) closest[i] = worst[static_cast<size_t>(5 * n) + i].value;
    clearance->Compute(data, &distances, &closest);  // data holds the poses InverseDynamics computed
    for (size_t i = 0; i < n_pairs; ++i) {
      ConstraintMargin& w = worst[static_cast<size_t>(5 * n) + i];
      const double margin = distances[i].distance - w.limit;
      if (margin < w.margin) w.margin = margin, w.time = t, w.value = distances[i].distance;
    }
  }
  for (const ConstraintMargin& m : worst) {
    if (std::isfinite(m.limit)) check.margins.push_back(m);
  }
  return check;
}

InfeasibleDesign::InfeasibleDesign(const std::string& summary, FeasibilityCheck check, std::vector<std::string> advice,
                                   bool before_search)
    : std::runtime_error([&] {
        std::string what = summary + "\n" + check.Explain();
        if (!advice.empty()) what += "to relax:\n";
        for (const std::string& a : advice) what += "  " + a + "\n";
        if (!what.empty() && what.back() == '\n') what.pop_back();
        return what;
      }()),
      check_(std::move(check)),
      advice_(std::move(advice)),
      before_search_(before_search) {}

std::vector<std::string> RelaxationAdvice(const FeasibilityCheck& check, const DesignOptions& options,
                                          bool before_search) {
  std::vector<std::string> advice;
  auto add = [&](const std::string& line) {
    if (std::find(advice.begin(), advice.end(), line) == advice.end()) advice.push_back(line);
  };
  const double ramp = options.ramp_seconds, motion_end = ramp + options.period_duration();
  bool in_motion = false;  // a violation outside the ramps
  for (const ConstraintMargin& m : check.margins) {
    if (m.margin >= 0.0) continue;
    const std::string joint = "joint " + std::to_string(m.joint + 1);
    if (!before_search && ramp > 0.0 && (m.time < ramp || m.time > motion_end)) {
      add(Format("--ramp (now %g s): longer ramps from and to the home pose (violated during t < %g s", ramp, ramp) +
          Format(" or t > %g s)", motion_end));
      continue;
    }
    in_motion = true;
    if (m.quantity == "clearance") {
      add(Format("--clearance (now %g m), or a --home pose with the links further apart", options.clearance));
    } else if (m.quantity == "q_min" || m.quantity == "q_max") {
      add(joint + "'s range q_min..q_max in the limits file" + (before_search ? ", or a --home inside it" : ""));
    } else if (m.quantity == "tau") {
      add(joint + "'s torque limit tau_max in the limits file, or a --home where gravity loads it less");
    } else {
      add(joint + "'s " + (m.quantity == "qd" ? "velocity limit qd_max" : "acceleration limit qdd_max") +
          " in the limits file, or fewer --harmonics, a lower --f0 or a longer --duration");
    }
  }
  if (!before_search && (in_motion || advice.empty())) {
    add(Format("--margin (now %g), which tightens every limit during the search", options.margin));
  }
  return advice;
}

namespace {

// The home pose: options.home when given (it must meet every limit, the
// ranges tightened by the margin, and the clearance), else FindHomePose.
// Throws InfeasibleDesign (before the search) when there is none; returns
// the home's source.
std::string ChooseHome(const RobotModel& model, const std::vector<JointLimits>& limits, const DesignOptions& options,
                       DesignProblem* problem) {
  const int n = model.n_dof();
  HomePose home;
  if (options.home.size() > 0) {
    if (options.home.size() != n) {
      throw std::invalid_argument("--home: expected " + std::to_string(n) + " joint angles, got " +
                                  std::to_string(options.home.size()));
    }
    home.q = options.home;
    home.source = "given";
  } else {
    home = FindHomePose(model, limits, options.margin, problem->clearance());
  }
  // The ranges as the search tightens them: the home must be inside.
  std::vector<JointLimits> tightened = limits;
  for (JointLimits& l : tightened) {
    const double range = l.q_max - l.q_min;
    if (std::isfinite(range)) l.q_min += options.margin * range, l.q_max -= options.margin * range;
  }
  FeasibilityCheck check = CheckPose(model, tightened, home.q, problem->clearance());
  if (!check.feasible()) {
    std::string pose;
    for (int j = 0; j < n; ++j) pose += (j ? "," : "") + Format("%.4g", home.q[j]);
    const std::string what = home.source == "given" ? "the --home pose " + pose
                                                    : "no pose with room to move was found; the nearest to the "
                                                      "middle of the joint ranges, " + pose + ",";
    std::vector<std::string> advice = RelaxationAdvice(check, options, true);
    // A searched home that ended at a joint's range (kept 10 % inside it,
    // home_pose.h): that range is what holds the pose where it is.
    for (int j = 0; j < n && home.source != "given"; ++j) {
      const JointLimits& l = limits[static_cast<size_t>(j)];
      const double range = l.q_max - l.q_min, inset = kHomeRangeRoom * range;
      if (!std::isfinite(range)) continue;
      if (std::abs(home.q[j] - (l.q_min + inset)) <= 1e-9 * range || std::abs(home.q[j] - (l.q_max - inset)) <= 1e-9 * range) {
        advice.push_back("joint " + std::to_string(j + 1) + "'s range q_min..q_max (" + Format("%g", l.q_min) + ".." +
                         Format("%g", l.q_max) + " rad) in the limits file: the search for a clear home stopped at it");
      }
    }
    throw InfeasibleDesign("no motion is possible with these settings: " + what +
                               " violates the limits (ranges tightened by the margin " + Format("%g", options.margin) +
                               ") or the clearance held still:",
                           std::move(check), std::move(advice), true);
  }
  problem->set_home(home.q);
  return home.source;
}

// The least-violating point any start ended at, checked at the check rate:
// thrown as InfeasibleDesign after the search.
[[noreturn]] void ExplainNoFeasibleStart(const RobotModel& model, const std::vector<JointLimits>& limits,
                                         const DesignOptions& options, const DesignProblem& problem,
                                         std::vector<StartRun>* runs) {
  int least = 0;
  double least_violation = kInf;
  for (size_t s = 0; s < runs->size(); ++s) {
    StartRun& run = (*runs)[s];
    if (run.last_theta.size() == 0) continue;
    const double* theta = run.last_theta.data();
    double violation = problem.MaxLinearViolation(theta);
    if (problem.n_nonlinear_constraints() > 0) {
      run.NonlinearFeasible(theta);
      violation = std::max(violation, *std::max_element(run.nonlinear_values.begin(), run.nonlinear_values.end()));
    }
    if (violation < least_violation) least_violation = violation, least = static_cast<int>(s);
  }
  const StartRun& run = (*runs)[static_cast<size_t>(least)];
  FeasibilityCheck check = CheckTrajectoryLimits(model, limits, problem.Trajectory(run.last_theta),
                                                 options.check_rate_hz, problem.clearance());
  std::vector<std::string> advice = RelaxationAdvice(check, options, false);
  throw InfeasibleDesign("no feasible design: no start met the limits (tightened by the margin " +
                             Format("%g", options.margin) + ") and the clearance on the sample grid; where start " +
                             std::to_string(least + 1) + " ended, checked at " + Format("%g", options.check_rate_hz) +
                             " Hz:",
                         std::move(check), std::move(advice), false);
}

}  // namespace

void CheckDesignFitsInMemory(const DesignRegressor& regressor, const DesignOptions& options) {
  // Per sample the regressor rows of every thread's workspace (two copies:
  // value and gradient), the limit rows and the basis; per start its
  // coefficient vectors (an estimate from above).
  const double n = regressor.model().n_dof(), p = regressor.n_parameters();
  const double coefficients = 2.0 * options.harmonics + 6.0;
  CheckFitsInMemory("--samples", options.samples, "samples",
                    8.0 * (2.0 * n * p * options.threads + 4.0 * n * coefficients + 3.0 * coefficients),
                    "the regressor rows, limit rows and basis of one sample");
  CheckFitsInMemory("--starts", options.starts, "starts", 8.0 * 4.0 * n * coefficients + 512.0,
                    "the coefficients and progress of one start");
}

DesignResult DesignExcitation(const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
                              const DesignOptions& options, const DesignControl& control) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  CheckDesignLimits(regressor.model(), limits);
  CheckDesignFitsInMemory(regressor, options);
  const auto t_begin = std::chrono::steady_clock::now();
  DesignProblem problem(regressor, limits, options);
  Eigen::VectorXd lower, upper;
  problem.Bounds(&lower, &upper);
  const std::string home_source = ChooseHome(regressor.model(), limits, options, &problem);

  std::vector<StartRun> runs(static_cast<size_t>(options.starts));
  std::vector<DesignStartSummary> summaries(runs.size());
  std::atomic<int> next{0};
  auto worker = [&]() {
    for (int s = next++; s < options.starts; s = next++) {
      StartRun& run = runs[static_cast<size_t>(s)];
      run.problem = &problem;
      run.options = &options;
      run.control = &control;
      run.index = s;
      run.ws.emplace(problem);
      Eigen::VectorXd theta = problem.StartPoint(options.seed + static_cast<unsigned>(s), &*run.ws);
      run.start_theta = theta;
      DesignStartSummary& summary = summaries[static_cast<size_t>(s)];
      summary.initial_value = problem.Criterion(theta.data(), nullptr, &*run.ws);
      summary.initial_violation = run.Violation(theta.data());
      run.best_value = kInf;
      if (run.Feasible(theta.data())) {
        run.best_value = summary.initial_value, run.best_theta = theta, run.feasible_at = 0;
      }

      // SLSQP takes the grid rows near the limits (see SelectRows), MMA and
      // COBYLA one max-row per limit. When SLSQP ends outside rows it did
      // not take, they join and it resumes from there; clearance is
      // constrained on the grid, and where the fine check finds the links
      // closer between grid instants, those instants join this start's grid
      // and the search resumes from its best point (at most twice).
      run.SelectRows(theta.data());
      nlopt_result result = run.Optimize(lower, upper, t_begin, &theta);
      for (int round = 0; round < 2 && problem.clearance() && run.best_theta.size() > 0 && run.Resumable(result);
           ++round) {
        const FeasibilityCheck fine = CheckTrajectoryLimits(regressor.model(), limits,
                                                            problem.Trajectory(run.best_theta),
                                                            options.check_rate_hz, problem.clearance());
        bool added = false;
        for (const ConstraintMargin& m : fine.margins) {
          if (m.quantity == "clearance" && m.margin < 0.0) problem.AddClearanceInstant(m.time, &*run.ws), added = true;
        }
        if (!added) break;
        theta = run.best_theta;
        run.best_value = kInf;
        run.best_theta.resize(0);
        run.SelectRows(theta.data());
        result = run.Optimize(lower, upper, t_begin, &theta);
      }
      run.last_theta = theta;
      summary.best_value = run.best_value;
      summary.evaluations = run.evaluations;
      summary.feasible_at = run.feasible_at;
      summary.status = result == NLOPT_FORCED_STOP ? "stopped" : nlopt_result_to_string(result);
      summary.final_violation = run.Violation(theta.data());
      DescribeProgress(&summary);
    }
  };
  std::vector<std::thread> pool;
  const int n_threads = std::min(options.threads, options.starts);
  for (int i = 1; i < n_threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  // The best feasible start; ties go to the lower index (deterministic).
  int best = -1;
  for (int s = 0; s < options.starts; ++s) {
    const StartRun& run = runs[static_cast<size_t>(s)];
    if (run.best_theta.size() > 0 && (best < 0 || run.best_value < runs[static_cast<size_t>(best)].best_value)) {
      best = s;
    }
  }
  if (best < 0) ExplainNoFeasibleStart(regressor.model(), limits, options, problem, &runs);
  const StartRun& winner = runs[static_cast<size_t>(best)];
  DesignResult result(problem.Trajectory(winner.best_theta), problem.Trajectory(winner.start_theta));
  result.starts = summaries;
  result.home = problem.home();
  result.home_source = home_source;
  for (const DesignStartSummary& s : summaries) result.evaluations += s.evaluations;
  result.initial_value = summaries[static_cast<size_t>(best)].initial_value;
  result.value = winner.best_value;
  const std::vector<double> times = DesignSampleTimes(options);
  result.initial = ComputeIdentifiability(regressor.Stack(result.initial_trajectory, times));
  const Eigen::MatrixXd W = regressor.Stack(result.trajectory, times);
  result.final = ComputeIdentifiability(W);
  if (result.final.rank < regressor.n_parameters()) {
    // Name what the limits leave unexcited (the least-squares classifier's reasons).
    const LeastSquaresSolution ls =
        SolveLeastSquares(W, Eigen::VectorXd::Zero(W.rows()), regressor.parameter_names());
    std::string unexcited;
    for (size_t i = 0; i < ls.identifiable.size(); ++i) {
      if (!ls.identifiable[i]) unexcited += "\n  " + ls.reason[i];
    }
    throw std::runtime_error("no design within these limits excites every parameter (rank " +
                             std::to_string(result.final.rank) + " of " + std::to_string(regressor.n_parameters()) +
                             "); check the limits of the joints involved:" + unexcited);
  }
  result.ramp_seconds = options.ramp_seconds;
  result.check = CheckTrajectoryLimits(regressor.model(), limits, result.RobotTrajectory(), options.check_rate_hz,
                                       problem.clearance());
  result.stopped = control.stop && control.stop->load();
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return result;
}

}  // namespace idbench
