#include "idbench/excitation/design_problem.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "idbench/excitation/excitation_design.h"

namespace idbench {
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kClearanceScale = 0.1;  // [m]: a clearance constraint value of 1 is 10 cm

}  // namespace

DesignProblem::Workspace::Workspace(const DesignProblem& p)
    : regressor(p.regressor_.model()),
      W(p.regressor_.rows_per_sample() * static_cast<Eigen::Index>(p.times_.size()), p.regressor_.n_parameters()),
      gx(3 * p.n_),
      x(p.times_.size(), JointState(p.n_)) {}

DesignProblem::DesignProblem(const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
                             const DesignOptions& options)
    : regressor_(regressor),
      limits_(limits),
      actuators_(options.actuators),
      criterion_(options.criterion),
      given_(options.given),
      f0_(options.f0),
      duration_(options.period_duration()),
      margin_(options.margin),
      rest_to_rest_(options.rest_to_rest),
      times_(DesignSampleTimes(options)) {
  n_ = regressor.model().n_dof();
  home_ = options.home;
  if (home_.size() != n_) {
    home_ = Eigen::VectorXd::Zero(n_);
    for (int j = 0; j < n_; ++j) {
      const JointLimits& l = limits_[static_cast<size_t>(j)];
      if (std::isfinite(l.q_min) && std::isfinite(l.q_max)) home_[j] = 0.5 * (l.q_min + l.q_max);
    }
  }
  H_ = options.harmonics;
  block_ = 2 * H_ + 1;
  for (double t : times_) bases_.push_back(FourierSeriesTrajectory::BasisAt(t, f0_, H_, duration_, rest_to_rest_));
  // The limit rows need 25 instants per period of the highest harmonic: they
  // miss a sinusoid's peak by at most 1 − cos(π/25) = 0.8 %, inside the margin
  // (and the result is re-checked at 1 kHz). Every stride-th sample when the
  // criterion has that many (fewer rows make SLSQP's quadratic subproblems
  // cheaper), else a grid of their own.
  const double top_periods = f0_ * H_ * duration_;
  const int wanted = static_cast<int>(std::ceil(25.0 * top_periods));
  if (static_cast<int>(times_.size()) >= wanted) {
    const size_t stride = times_.size() / static_cast<size_t>(wanted);
    for (size_t k = 0; k < times_.size(); k += stride) row_times_.push_back(times_[k]);
  } else {
    DesignOptions row_grid = options;
    row_grid.samples = wanted;
    row_times_ = DesignSampleTimes(row_grid);
  }
  BuildLinearRows();
  // The torque limits: each joint's, then each motor's through A⁻ᵀ.
  for (int j = 0; j < n_; ++j) {
    const double tau_max = limits_[static_cast<size_t>(j)].tau_max;
    if (!std::isfinite(tau_max)) continue;
    torque_limits_.push_back({Eigen::VectorXd::Unit(n_, j), tau_max,
                              "torque limit of joint '" + regressor.model().link(j).joint_name + "'"});
  }
  if (!actuators_.empty()) {
    const Eigen::MatrixXd motor_from_joint = actuators_.MotorTorqueFromJoint();
    for (int k = 0; k < n_; ++k) {
      const double tau_max = actuators_.motors[static_cast<size_t>(k)].tau_max;
      if (!std::isfinite(tau_max)) continue;
      torque_limits_.push_back({motor_from_joint.row(k).transpose(), tau_max,
                                "torque limit of motor " + std::to_string(k + 1) + " (joints " +
                                    actuators_.DrivenJoints(regressor.model(), k) + ")"});
    }
  }
  clearance_ = options.MakeClearance(regressor.model());
  if (clearance_) {
    clearance_stride_ = (options.samples + 99) / 100;
    set_home(home_);
  }
  if (n_torque_constraints() > 0) {
    FrictionModel full;
    full.viscous = full.coulomb = full.rotor_inertia = true;
    torque_regressor_.emplace(DesignRegressor::JointTorque(regressor.model(), full));
  }
}

void DesignProblem::set_home(const Eigen::VectorXd& q) {
  home_ = q;
  if (!clearance_) return;
  // The search keeps 1 mm more than asked, so that the fine check passes
  // between the grid instants (as the margin does for the other limits);
  // only as much as the pair has at the home pose (none for a pair held at
  // its distance at q = 0: the home pose itself must stay feasible).
  constexpr double kSlack = 1e-3;  // [m]
  const RobotModel& model = regressor_.model();
  KinematicsData<double> k(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  ComputeKinematicsT<double>(model, q, zero, zero, &k);
  std::vector<Clearance> at_home;
  clearance_->Compute(k, &at_home);
  clearance_slack_.resize(at_home.size());
  for (size_t i = 0; i < at_home.size(); ++i) {
    clearance_slack_[i] = std::clamp(at_home[i].distance - clearance_->pairs()[i].minimum, 0.0, kSlack);
  }
}

int DesignProblem::n_torque_constraints() const {
  return static_cast<int>(torque_limits_.size());
}

int DesignProblem::n_nonlinear_constraints() const {
  return n_torque_constraints() + (clearance_ ? static_cast<int>(clearance_->pairs().size()) : 0);
}

FourierSeriesTrajectory DesignProblem::Trajectory(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd q0(n_);
  Eigen::MatrixXd a(n_, H_), b(n_, H_);
  for (int j = 0; j < n_; ++j) {
    q0[j] = theta[j * block_];
    a.row(j) = theta.segment(j * block_ + 1, H_).transpose();
    b.row(j) = theta.segment(j * block_ + 1 + H_, H_).transpose();
  }
  return FourierSeriesTrajectory(q0, a, b, f0_, duration_, rest_to_rest_);
}

double DesignProblem::LinearValue(const LinearRow& row, const double* theta) const {
  return row.coefficients.dot(Eigen::Map<const Eigen::VectorXd>(theta + row.joint * block_, row.coefficients.size())) -
         row.rhs;
}

double DesignProblem::MaxLinearViolation(const double* theta) const {
  double worst = -kInfinity;
  for (const LinearRow& row : rows_) worst = std::max(worst, LinearValue(row, theta));
  return worst;
}

void DesignProblem::States(const double* theta, Workspace* ws) const {
  for (size_t k = 0; k < times_.size(); ++k) {
    JointState& x = ws->x[k];
    for (int j = 0; j < n_; ++j) {
      const Eigen::Map<const Eigen::VectorXd> c(theta + j * block_ + 1, 2 * H_);
      x.q[j] = theta[j * block_] + bases_[k].q.dot(c);
      x.qd[j] = bases_[k].qd.dot(c);
      x.qdd[j] = bases_[k].qdd.dot(c);
    }
  }
}

void DesignProblem::ChainToUnknowns(const FourierBasis& basis, const Eigen::VectorXd& gx, double* g) const {
  for (int j = 0; j < n_; ++j) {
    g[j * block_] += gx[j];
    Eigen::Map<Eigen::VectorXd>(g + j * block_ + 1, 2 * H_) +=
        gx[j] * basis.q + gx[n_ + j] * basis.qd + gx[2 * n_ + j] * basis.qdd;
  }
}

JointState DesignProblem::StateAt(const FourierBasis& basis, const double* theta) const {
  JointState x(n_);
  for (int j = 0; j < n_; ++j) {
    const Eigen::Map<const Eigen::VectorXd> c(theta + j * block_ + 1, 2 * H_);
    x.q[j] = theta[j * block_] + basis.q.dot(c);
    x.qd[j] = basis.qd.dot(c);
    x.qdd[j] = basis.qdd.dot(c);
  }
  return x;
}

void DesignProblem::AddClearanceInstant(double t, Workspace* ws) const {
  ws->clearance_extra.push_back(FourierSeriesTrajectory::BasisAt(t, f0_, H_, duration_, rest_to_rest_));
  ws->clearance_extra_t.push_back(t);
}

double DesignProblem::Criterion(const double* theta, double* grad, Workspace* ws) const {
  States(theta, ws);
  const int r = regressor_.rows_per_sample();
  for (size_t k = 0; k < times_.size(); ++k) {
    regressor_.Rows(ws->x[k], &ws->regressor, ws->W.middleRows(r * static_cast<Eigen::Index>(k), r));
  }
  const double c = EvaluateDesignCriterion(criterion_, ws->W, grad ? &ws->G : nullptr, given_);
  if (grad) std::fill(grad, grad + n_unknowns(), 0.0);
  if (!std::isfinite(c)) return kRankDeficientValue;
  if (!grad) return c;
  for (size_t k = 0; k < times_.size(); ++k) {
    regressor_.StateGradient(ws->x[k], ws->G.middleRows(r * static_cast<Eigen::Index>(k), r), &ws->regressor,
                             ws->gx);
    ChainToUnknowns(bases_[k], ws->gx, grad);
  }
  return c;
}

void DesignProblem::NonlinearConstraints(const double* theta, double* result, double* grad, Workspace* ws) const {
  States(theta, ws);
  if (clearance_) {
    ClearanceConstraints(theta, result + n_torque_constraints(),
                         grad ? grad + static_cast<size_t>(n_torque_constraints()) * static_cast<size_t>(n_unknowns())
                              : nullptr,
                         ws);
  }
  if (n_torque_constraints() == 0) return;
  const DesignRegressor& tr = *torque_regressor_;
  Eigen::MatrixXd& rows = ws->torque_rows;
  rows.resize(n_, tr.n_parameters());
  const int m = n_torque_constraints();
  Eigen::VectorXd worst = Eigen::VectorXd::Constant(m, -kInfinity), sign = Eigen::VectorXd::Ones(m);
  std::vector<size_t> at(static_cast<size_t>(m), 0);
  for (size_t k = 0; k < times_.size(); ++k) {
    tr.Rows(ws->x[k], &ws->regressor, rows);
    const Eigen::VectorXd tau = rows * tr.true_parameters();
    for (int i = 0; i < m; ++i) {
      const double v = torque_limits_[static_cast<size_t>(i)].weights.dot(tau);
      if (std::abs(v) > worst[i]) {
        worst[i] = std::abs(v);
        sign[i] = v >= 0.0 ? 1.0 : -1.0;
        at[static_cast<size_t>(i)] = k;
      }
    }
  }
  for (int i = 0; i < m; ++i) {
    const TorqueLimit& limit = torque_limits_[static_cast<size_t>(i)];
    result[i] = worst[i] / limit.limit - (1.0 - margin_);
    if (grad) {
      // ∂|w·τ|/∂x at the worst sample: ⟨G, Rows⟩ with G = sign w βᵀ / τ_max.
      const size_t k = at[static_cast<size_t>(i)];
      const Eigen::MatrixXd G = sign[i] / limit.limit * limit.weights * tr.true_parameters().transpose();
      tr.StateGradient(ws->x[k], G, &ws->regressor, ws->gx);
      double* g = grad + static_cast<size_t>(i) * static_cast<size_t>(n_unknowns());
      std::fill(g, g + n_unknowns(), 0.0);
      ChainToUnknowns(bases_[k], ws->gx, g);
    }
  }
}

std::string DesignProblem::NonlinearConstraintName(int i) const {
  if (i >= n_torque_constraints()) {
    const ClearancePair& pair = clearance_->pairs()[static_cast<size_t>(i - n_torque_constraints())];
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g m", pair.minimum);
    return "clearance '" + pair.Name(regressor_.model()) + "' >= " + buf +
           (pair.minimum < clearance_->min_clearance() ? " (its distance at q = 0)" : "");
  }
  return torque_limits_[static_cast<size_t>(i)].name;
}

std::string DesignProblem::DescribeViolation(int i, double c) const {
  char buf[64];
  if (i >= n_torque_constraints()) std::snprintf(buf, sizeof buf, " by %.3g m", c * kClearanceScale);
  else std::snprintf(buf, sizeof buf, " by %.3g %% of it", 100.0 * c);
  return NonlinearConstraintName(i) + buf;
}

void DesignProblem::ClearanceConstraints(const double* theta, double* result, double* grad, Workspace* ws) const {
  constexpr double kScale = kClearanceScale;
  const RobotModel& model = regressor_.model();
  // The instants: every clearance_stride_-th grid sample, then those added.
  std::vector<const FourierBasis*> instants;
  for (size_t s = 0; s < times_.size(); s += static_cast<size_t>(clearance_stride_)) instants.push_back(&bases_[s]);
  for (const FourierBasis& b : ws->clearance_extra) instants.push_back(&b);
  const size_t n_pairs = clearance_->pairs().size(), n_instants = instants.size();
  // The link poses at every instant, and each pair's lower bound there: its
  // bounding capsules' (no GJK), or what the last evaluation knew there less
  // how far the joints have moved both sides since (ClearancePair::reach).
  while (ws->clearance_poses.size() < n_instants) ws->clearance_poses.emplace_back(model);
  std::vector<double>& bounds = ws->clearance_bounds;
  bounds.resize(n_instants * n_pairs);
  ws->clearance_q.resize(n_, static_cast<Eigen::Index>(n_instants));
  const bool carried = ws->clearance_known.size() == n_instants * n_pairs;  // the same instants as then
  for (size_t s = 0; s < n_instants; ++s) {
    const JointState x = StateAt(*instants[s], theta);
    ws->clearance_q.col(static_cast<Eigen::Index>(s)) = x.q;
    ComputeKinematicsT<double>(model, x.q, x.qd, x.qdd, &ws->clearance_poses[s]);
    for (size_t i = 0; i < n_pairs; ++i) {
      double bound = clearance_->LowerBound(ws->clearance_poses[s], static_cast<int>(i));
      if (carried) {
        const std::vector<double>& reach = clearance_->pairs()[i].reach;
        double known = ws->clearance_known[s * n_pairs + i];
        for (int j = 0; j < n_ && known > bound; ++j) {
          known -= reach[static_cast<size_t>(j)] * std::abs(x.q[j] - ws->clearance_known_q(j, static_cast<Eigen::Index>(s)));
        }
        bound = std::max(bound, known);
      }
      bounds[s * n_pairs + i] = bound;
    }
  }
  // A pair whose bound stays kFar above what it must keep at every instant
  // is certified inactive: one GJK, at the instant of least bound, gives its
  // value and gradient (a linearisation that still holds SLSQP's steps back,
  // as an exact one does; its value is below the exact one, both < −0.2).
  // The exact minimum of such a pair would take GJK at every instant where
  // its distance hardly changes (a shoulder link over the floor).
  constexpr double kFar = 0.02;  // [m]
  std::vector<char> far(n_pairs, 0);
  std::vector<size_t> at(n_pairs, 0);
  for (size_t i = 0; i < n_pairs; ++i) {
    for (size_t s = 1; s < n_instants; ++s) {
      if (bounds[s * n_pairs + i] < bounds[at[i] * n_pairs + i]) at[i] = s;
    }
    const double least = bounds[at[i] * n_pairs + i];
    const double keep = clearance_->pairs()[i].minimum + clearance_slack_[i];
    far[i] = least > keep + kFar;
  }
  ws->clearance_known = bounds;
  // Each pair's minimum over the instants (branch and bound): GJK at the
  // instants in the order of their bounds, until the next bound is above the
  // least distance found; an instant is also skipped when a distance found
  // at another instant, less how far the joints between can move the two
  // sides (ClearancePair::reach), is above it. The minimum over all
  // instants (the earliest instant on ties) to GJK's accuracy, with its
  // witness points.
  constexpr double kGjkTolerance = 1e-7;  // [m]
  const size_t n_grid = n_instants - ws->clearance_extra.size();
  auto instant_time = [&](size_t s) {
    return s < n_grid ? times_[s * static_cast<size_t>(clearance_stride_)] : ws->clearance_extra_t[s - n_grid];
  };
  ws->clearance_refined.assign(n_pairs, 0);
  if (ws->clearance_refined_pose.size() < n_pairs + 1) {
    ws->clearance_refined_pose.resize(n_pairs + 1, KinematicsData<double>(model));
    ws->clearance_refined_basis.resize(n_pairs);
  }
  std::vector<Clearance> witness(n_pairs);
  std::vector<size_t>& order = ws->clearance_order;
  order.resize(n_instants);
  for (size_t i = 0; i < n_pairs; ++i) {
    const ClearancePair& pair = clearance_->pairs()[i];
    if (far[i]) {
      witness[i] = clearance_->ComputePair(ws->clearance_poses[at[i]], static_cast<int>(i));
      double& known = ws->clearance_known[at[i] * n_pairs + i];
      known = std::max(known, witness[i].distance - kGjkTolerance);
      result[i] = (pair.minimum + clearance_slack_[i] - witness[i].distance) / kScale;
      continue;
    }
    at[i] = 0;
    for (size_t s = 0; s < n_instants; ++s) order[s] = s;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      const double ba = bounds[a * n_pairs + i], bb = bounds[b * n_pairs + i];
      return ba < bb || (ba == bb && a < b);
    });
    double best = kInfinity;
    const std::vector<double>& reach = clearance_->pairs()[i].reach;
    ws->clearance_done.clear();
    ws->clearance_done_distance.clear();
    auto beaten = [&](double bound, size_t s) { return bound > best || (bound == best && s > at[i]); };
    for (size_t s : order) {
      const double bound = bounds[s * n_pairs + i];
      if (beaten(bound, s)) break;
      // The bound from the instants already measured (their joint motion to s).
      double moved_bound = -kInfinity;
      for (size_t e = 0; e < ws->clearance_done.size(); ++e) {
        double d = ws->clearance_done_distance[e] - kGjkTolerance;
        const size_t se = ws->clearance_done[e];
        for (int j = 0; j < n_ && d >= best; ++j) {  // stops once below best: not beaten
          d -= reach[static_cast<size_t>(j)] *
               std::abs(ws->clearance_q(j, static_cast<Eigen::Index>(s)) - ws->clearance_q(j, static_cast<Eigen::Index>(se)));
        }
        moved_bound = std::max(moved_bound, d);
      }
      if (beaten(moved_bound, s)) continue;
      const Clearance c = clearance_->ComputePair(ws->clearance_poses[s], static_cast<int>(i),
                                                  std::isfinite(best) ? std::nextafter(best, kInfinity) : kInfinity);
      if (c.distance < best || (c.distance == best && s < at[i])) best = c.distance, at[i] = s, witness[i] = c;
      // Exact, or (pruned) a lower bound of the distance at s: either bounds the others.
      ws->clearance_done.push_back(s);
      ws->clearance_done_distance.push_back(c.distance);
      double& known = ws->clearance_known[s * n_pairs + i];
      known = std::max(known, c.distance - kGjkTolerance);
    }
    RefineClearanceMinimum(theta, static_cast<int>(i), instant_time(at[i]), &best, &witness[i], ws);
    result[i] = (pair.minimum + clearance_slack_[i] - best) / kScale;
  }
  ws->clearance_known_q = ws->clearance_q;
  if (!grad) return;
  // The gradients from the witness points at each pair's closest instant.
  for (size_t i = 0; i < n_pairs; ++i) {
    double* g = grad + i * static_cast<size_t>(n_unknowns());
    std::fill(g, g + n_unknowns(), 0.0);
    const bool refined = ws->clearance_refined[i];
    const Eigen::VectorXd dd_dq = clearance_->DistanceGradient(
        model, refined ? ws->clearance_refined_pose[i] : ws->clearance_poses[at[i]], clearance_->pairs()[i],
        witness[i]);
    ws->gx.setZero();
    ws->gx.head(n_) = -dd_dq / kScale;
    ChainToUnknowns(refined ? ws->clearance_refined_basis[i] : *instants[at[i]], ws->gx, g);
  }
}

void DesignProblem::RefineClearanceMinimum(const double* theta, int i, double t, double* distance,
                                           Clearance* witness, Workspace* ws) const {
  // Between grid instants the links may pass closer than at either. A
  // descent over the times an eighth of the grid spacing apart (a fixed finer
  // grid, so the value stays continuous in θ while the dip stays in one
  // place) from the closest instant finds that dip to within its curvature
  // over a sixteenth of the spacing (well within the 1 mm slack: 0.27 mm in
  // the test's fastest motions), where the 1 kHz check would otherwise find
  // it and a repair round add the instant. (The instants either side are no
  // closer: the grid's minimum.)
  constexpr int kSteps = 8;
  const size_t stride = static_cast<size_t>(clearance_stride_);
  if (times_.size() <= stride) return;
  const double t_lo = times_.front(), t_hi = times_.back();
  const double step = (times_[stride] - times_[0]) / kSteps;
  const RobotModel& model = regressor_.model();
  KinematicsData<double>& pose = ws->clearance_refined_pose[static_cast<size_t>(i)];
  KinematicsData<double>& trial = ws->clearance_refined_pose.back();
  FourierBasis basis;
  // Whether the time k steps from t is closer than *distance (then kept).
  auto closer = [&](int k) {
    const double ts = t + k * step;
    if (ts < t_lo || ts > t_hi) return false;
    basis = FourierSeriesTrajectory::BasisAt(ts, f0_, H_, duration_, rest_to_rest_);
    const JointState x = StateAt(basis, theta);
    ComputeKinematicsT<double>(model, x.q, x.qd, x.qdd, &trial);
    const Clearance c = clearance_->ComputePair(trial, i, std::nextafter(*distance, kInfinity));
    if (!(c.distance < *distance)) return false;
    *distance = c.distance, *witness = c;
    std::swap(pose, trial);
    ws->clearance_refined_basis[static_cast<size_t>(i)] = basis;
    ws->clearance_refined[static_cast<size_t>(i)] = 1;
    return true;
  };
  const int direction = closer(1) ? 1 : closer(-1) ? -1 : 0;
  for (int k = 2 * direction; direction != 0 && std::abs(k) < kSteps && closer(k); k += direction) {
  }
}

Eigen::VectorXd DesignProblem::StartPoint(unsigned seed, Workspace* ws, std::vector<std::string>* held_still) const {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(n_unknowns());
  for (int j = 0; j < n_; ++j) {
    theta[j * block_] = home_[j];
    for (int h = 0; h < H_; ++h) {
      theta[j * block_ + 1 + h] = normal(rng) / (h + 1);
      theta[j * block_ + 1 + H_ + h] = normal(rng) / (h + 1);
    }
  }
  // Each joint's rows are affine in the scale s_j of its coefficients:
  // s_j (c·coef) + c₀ q0 ≤ rhs; every joint goes to 90 % of its tightest row.
  std::vector<double> scale(static_cast<size_t>(n_), kInfinity);
  for (const LinearRow& row : rows_) {
    if (row.span(block_) != 1) continue;
    const Eigen::VectorXd block = theta.segment(row.joint * block_, block_);
    const double offset = row.coefficients[0] * block[0];
    const double slope = row.coefficients.tail(2 * H_).dot(block.tail(2 * H_));
    double& s = scale[static_cast<size_t>(row.joint)];
    if (slope > 0.0) s = std::min(s, (row.rhs - offset) / slope);
  }
  for (int j = 0; j < n_; ++j) {
    theta.segment(j * block_ + 1, 2 * H_) *= 0.9 * std::max(0.0, scale[static_cast<size_t>(j)]);
  }
  // A motor's rows (no offset: velocities) span the joints it drives; where
  // one goes past 90 % of its limit, those joints slow down together.
  for (const LinearRow& row : rows_) {
    if (row.span(block_) == 1) continue;
    const double value = LinearValue(row, theta.data()) + row.rhs;
    if (value <= 0.9 * row.rhs) continue;
    const double factor = 0.9 * row.rhs / value;
    for (int j = row.joint; j < row.joint + row.span(block_); ++j) theta.segment(j * block_ + 1, 2 * H_) *= factor;
  }
  if (n_nonlinear_constraints() == 0) return theta;
  // The motion scaled by s about the home pose: 0.8 of the largest s in
  // [1/1024, 1] (bisection) whose torque and clearance constraints hold on
  // the grid. Not the largest: a start on a clearance constraint's boundary
  // left SLSQP without a feasible step (UR10e-like arm: no start improved,
  // cond 1405; from 0.8 of it, cond 37).
  std::vector<double> values(static_cast<size_t>(n_nonlinear_constraints()));
  auto scaled = [&](double s) {
    Eigen::VectorXd t = theta;
    for (int j = 0; j < n_; ++j) t.segment(j * block_ + 1, 2 * H_) *= s;
    return t;
  };
  auto feasible = [&](const Eigen::VectorXd& t) {
    NonlinearConstraints(t.data(), values.data(), nullptr, ws);
    return *std::max_element(values.begin(), values.end()) <= 0.0;
  };
  if (feasible(theta)) return theta;
  // A joint whose motion alone, at 1/1024 of its amplitude, breaks a
  // constraint is held still (a clearance pair held at its distance at q = 0
  // that any motion of the joint reduces): the others can still move.
  if (!feasible(scaled(1.0 / 1024.0))) {
    for (int j = 0; j < n_; ++j) {
      Eigen::VectorXd alone = scaled(0.0);
      alone.segment(j * block_ + 1, 2 * H_) = theta.segment(j * block_ + 1, 2 * H_) / 1024.0;
      if (feasible(alone)) continue;
      theta.segment(j * block_ + 1, 2 * H_).setZero();
      if (held_still) {
        const size_t worst = static_cast<size_t>(std::max_element(values.begin(), values.end()) - values.begin());
        held_still->push_back("joint '" + regressor_.model().link(j).joint_name + "' (its motion alone breaks the " +
                              NonlinearConstraintName(static_cast<int>(worst)) + ")");
      }
    }
  }
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 10; ++i) {
    const double mid = 0.5 * (lo + hi);
    (feasible(scaled(mid)) ? lo : hi) = mid;
  }
  Eigen::VectorXd start = scaled(std::max(0.8 * lo, 1.0 / 1024.0));
  if (lo <= 0.0) return start;
  // Then each joint grows on its own (bisection on its factor up to its
  // kinematic scale, 0.8 of the largest that stays feasible): the joints
  // that do not bring links closer need not stay as small as those that do.
  for (int j = 0; j < n_; ++j) {
    const Eigen::VectorXd base = start;
    auto grown = [&](double f) {
      Eigen::VectorXd t = base;
      t.segment(j * block_ + 1, 2 * H_) *= f;
      return t;
    };
    double g_lo = 1.0, g_hi = 1.0 / (0.8 * lo);
    if (feasible(grown(g_hi))) g_lo = g_hi;
    for (int i = 0; i < 6 && g_lo < g_hi; ++i) {
      const double mid = std::sqrt(g_lo * g_hi);
      (feasible(grown(mid)) ? g_lo : g_hi) = mid;
    }
    start = grown(std::max(1.0, 0.8 * g_lo));
  }
  return start;
}

void DesignProblem::Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
  *lower = Eigen::VectorXd(n_unknowns());
  *upper = Eigen::VectorXd(n_unknowns());
  for (int j = 0; j < n_; ++j) {
    const JointLimits& l = limits_[static_cast<size_t>(j)];
    (*lower)[j * block_] = std::isfinite(l.q_min) ? l.q_min : -1e3;
    (*upper)[j * block_] = std::isfinite(l.q_max) ? l.q_max : 1e3;
    lower->segment(j * block_ + 1, 2 * H_).setConstant(-2.0 * l.qd_max);
    upper->segment(j * block_ + 1, 2 * H_).setConstant(2.0 * l.qd_max);
  }
}

void DesignProblem::BuildLinearRows() {
  const double m = margin_;
  for (int j = 0; j < n_; ++j) {
    const JointLimits& l = limits_[static_cast<size_t>(j)];
    const double range = l.q_max - l.q_min;
    for (double t : row_times_) {
      const FourierBasis w = FourierSeriesTrajectory::BasisAt(t, f0_, H_, duration_, rest_to_rest_);
      auto add = [&](int quantity, double sign, double offset_coefficient, const Eigen::VectorXd& weights,
                     double limit, double scale) {
        LinearRow row;
        row.joint = j;
        row.group = 4 * j + quantity;
        row.coefficients.resize(block_);
        row.coefficients[0] = sign * offset_coefficient / scale;
        row.coefficients.tail(2 * H_) = sign * weights / scale;
        row.rhs = limit / scale;
        rows_.push_back(std::move(row));
      };
      if (std::isfinite(range)) {
        add(0, 1.0, 1.0, w.q, l.q_max - m * range, range);
        add(3, -1.0, 1.0, w.q, -(l.q_min + m * range), range);
      }
      add(1, 1.0, 0.0, w.qd, (1 - m) * l.qd_max, l.qd_max);
      add(1, -1.0, 0.0, w.qd, (1 - m) * l.qd_max, l.qd_max);
      add(2, 1.0, 0.0, w.qdd, (1 - m) * l.qdd_max, l.qdd_max);
      add(2, -1.0, 0.0, w.qdd, (1 - m) * l.qdd_max, l.qdd_max);
    }
  }
  // Each motor's velocity θ̇m_k = Σ_j A(k, j)·q̇_j over the joints it drives
  // (the span of its row's non-zeros), as the joints' velocity rows.
  for (int k = 0; k < static_cast<int>(actuators_.motors.size()); ++k) {
    const double qd_max = actuators_.motors[static_cast<size_t>(k)].qd_max;
    if (!std::isfinite(qd_max)) continue;
    const Eigen::VectorXd a = actuators_.transmission.actuator_from_joint.row(k).transpose();
    int first = 0, last = n_ - 1;
    while (first < last && a[first] == 0.0) ++first;
    while (last > first && a[last] == 0.0) --last;
    has_motor_rows_ = true;
    for (double t : row_times_) {
      const FourierBasis w = FourierSeriesTrajectory::BasisAt(t, f0_, H_, duration_, rest_to_rest_);
      for (double sign : {1.0, -1.0}) {
        LinearRow row;
        row.joint = first;
        row.group = 4 * n_ + k;
        row.coefficients = Eigen::VectorXd::Zero((last - first + 1) * block_);
        for (int j = first; j <= last; ++j) {
          row.coefficients.segment((j - first) * block_ + 1, 2 * H_) = sign * a[j] / qd_max * w.qd;
        }
        row.rhs = 1.0 - m;
        rows_.push_back(std::move(row));
      }
    }
  }
}

}  // namespace idbench
