// The excitation design's multi-start driver, DesignExcitation, and its
// options and input checks (excitation_design.h). One start's search is in
// design_start.cc, its outcome in design_outcome.cc, the re-check in
// feasibility_check.cc.
#include "idbench/excitation/excitation_design.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>

#include "design_outcome.h"
#include "design_start.h"
#include "excitation_design_internal.h"
#include "idbench/engine/resource_limits.h"
#include "idbench/excitation/design_problem.h"
#include "idbench/excitation/home_pose.h"

namespace idbench {
namespace {

using internal::Format;
using internal::StartRun;

}  // namespace

std::vector<std::string> DesignAlgorithmNames() { return kDesignAlgorithmNames.Names(); }
std::string DesignAlgorithmName(DesignAlgorithm algorithm) {
  return std::string(kDesignAlgorithmNames.Name(algorithm));
}
bool ParseDesignAlgorithm(std::string_view text, DesignAlgorithm* algorithm, std::string* why) {
  return kDesignAlgorithmNames.Parse(text, algorithm, why);
}

bool DesignOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (harmonics < 1 || harmonics > FourierSeriesTrajectory::kMaxHarmonics) {
    return fail("harmonics: must be in 1.." + std::to_string(FourierSeriesTrajectory::kMaxHarmonics) + ", got " +
                std::to_string(harmonics));
  }
  if (!(f0 > 0.0) || !(f0 <= 100.0)) return fail(Format("f0: must be in (0, 100] Hz, got %g", f0));
  if (!(duration >= 0.0) || !std::isfinite(duration)) return fail(Format("duration: must be >= 0 s, got %g", duration));
  const double top = f0 * harmonics * period_duration();  // periods of the top harmonic
  if (samples < 8 * top) {
    return fail(Format("samples: must be at least %g (8 per period of the highest harmonic, %g Hz), got %g",
                       std::ceil(8 * top), f0 * harmonics, samples));
  }
  if (starts < 1) return fail("starts: must be >= 1, got " + std::to_string(starts));
  if (threads < 1 || threads > MaxThreads()) {
    return fail("threads: must be in 1.." + std::to_string(MaxThreads()) + " (4 per hardware thread), got " +
                std::to_string(threads));
  }
  if (max_evaluations < 1) return fail("max_evaluations: must be >= 1");
  if (!(max_seconds >= 0.0)) return fail("max_seconds: must be >= 0");
  if (!(margin >= 0.0 && margin < 0.5)) return fail(Format("margin: must be in [0, 0.5), got %g", margin));
  if (!std::isfinite(clearance) || clearance > 1.0) return fail(Format("clearance: must be at most 1 m, got %g", clearance));
  if (!(check_rate_hz > 0.0)) return fail("the check rate must be > 0 Hz");
  if (std::string scene_why; !scene.IsValid(&scene_why)) return fail("scene." + scene_why);
  if (!base_pose.IsValid(why)) return false;
  if (!(ramp_seconds >= 0.0 && ramp_seconds <= kMaxRampSeconds)) {
    return fail(Format("ramp_seconds: must be in [0, %g] s, got ", kMaxRampSeconds) + Format("%g", ramp_seconds));
  }
  return true;
}

std::optional<ClearanceModel> DesignOptions::MakeClearance(const RobotModel& model) const {
  if (clearance < 0.0 || std::none_of(model.links().begin(), model.links().end(),
                                      [](const Link& l) { return !l.CollisionShapes().empty(); })) {
    return std::nullopt;
  }
  return std::optional<ClearanceModel>(std::in_place, model, clearance, scene, base_pose);
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
                                  Format("%g", l.qd_max) + " (give it in the `limits` file)");
    }
    if (!(l.qdd_max > 0.0) || !std::isfinite(l.qdd_max)) {
      throw std::invalid_argument(who + ": the acceleration limit qdd_max must be finite and > 0, got " +
                                  Format("%g", l.qdd_max) + " (give it in the `limits` file)");
    }
    if (!(l.q_min < l.q_max)) {
      throw std::invalid_argument(who + Format(": q_min = %g must be below q_max = %g rad", l.q_min, l.q_max));
    }
    if (!(l.tau_max > 0.0)) throw std::invalid_argument(who + Format(": tau_max must be > 0, got %g", l.tau_max));
  }
}

namespace {

// The home pose: options.home when given (it must meet every limit, the
// ranges tightened by the margin, the motors' torque limits, and the
// clearance), else FindHomePose.
// Returns the home's source, or (before the search) the explanation when
// there is none, in *none.
std::string ChooseHome(const RobotModel& model, const std::vector<JointLimits>& limits, const DesignOptions& options,
                       DesignProblem* problem, std::optional<std::pair<Eigen::VectorXd, DesignInfeasibility>>* none) {
  const int n = model.n_dof();
  HomePose home;
  if (options.home.size() > 0) {
    if (options.home.size() != n) {
      throw std::invalid_argument("home: expected " + std::to_string(n) + " joint angles, got " +
                                  std::to_string(options.home.size()));
    }
    home.q = options.home;
    home.source = "given";
  } else {
    home = FindHomePose(model, limits, options.margin, problem->clearance(), options.actuators);
  }
  // The ranges as the search tightens them: the home must be inside.
  std::vector<JointLimits> tightened = limits;
  for (JointLimits& l : tightened) {
    const double range = l.q_max - l.q_min;
    if (std::isfinite(range)) l.q_min += options.margin * range, l.q_max -= options.margin * range;
  }
  FeasibilityCheck check = CheckPose(model, tightened, home.q, problem->clearance(), options.actuators);
  if (!check.feasible()) {
    std::string pose;
    for (int j = 0; j < n; ++j) pose += (j ? "," : "") + Format("%.4g", home.q[j]);
    const std::string what = home.source == "given" ? "the `home` pose " + pose
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
    none->emplace(home.q, internal::ExplainInfeasibility(
                              "no motion is possible with these settings: " + what +
                                  " violates the limits (ranges tightened by the margin " +
                                  Format("%g", options.margin) + ") or the clearance held still:",
                              std::move(check), std::move(advice), true));
    return home.source;
  }
  problem->set_home(home.q);
  return home.source;
}

}  // namespace

void CheckDesignFitsInMemory(const DesignRegressor& regressor, const DesignOptions& options) {
  // Per sample the regressor rows of every thread's workspace (two copies:
  // value and gradient), the limit rows and the basis; per start its
  // coefficient vectors (an estimate from above).
  const double n = regressor.model().n_dof(), p = regressor.n_parameters();
  const double coefficients = 2.0 * options.harmonics + 6.0;
  CheckFitsInMemory("samples", options.samples, "samples",
                    8.0 * (2.0 * n * p * options.threads + 4.0 * n * coefficients + 3.0 * coefficients),
                    "the regressor rows, limit rows and basis of one sample");
  CheckFitsInMemory("starts", options.starts, "starts", 8.0 * 4.0 * n * coefficients + 512.0,
                    "the coefficients and progress of one start");
}

DesignResult DesignExcitation(const DesignRegressor& regressor, const std::vector<JointLimits>& limits,
                              const DesignOptions& options, const DesignControl& control) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (!IsMountedAt(regressor.model(), options.base_pose)) {
    const Eigen::Vector3d g = regressor.model().gravity_W(), want = MountedGravity(regressor.model(), options.base_pose);
    throw std::invalid_argument(Format("base_pose: the model's gravity (%g, %g, %g)", g.x(), g.y(), g.z()) +
                                Format(" is not the world's -z seen from this base (%g, %g, %g); mount the model "
                                       "(MountRobot)", want.x(), want.y(), want.z()));
  }
  CheckDesignLimits(regressor.model(), limits);
  options.actuators.Check(regressor.model().n_dof());
  CheckDesignFitsInMemory(regressor, options);
  const auto t_begin = std::chrono::steady_clock::now();
  DesignProblem problem(regressor, limits, options);
  Eigen::VectorXd lower, upper;
  problem.Bounds(&lower, &upper);
  std::optional<std::pair<Eigen::VectorXd, DesignInfeasibility>> no_home;
  const std::string home_source = ChooseHome(regressor.model(), limits, options, &problem, &no_home);
  auto seconds_since_begin = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  };
  if (no_home) {  // no motion before the search: the result holds still at the rejected home
    const int n_dof = regressor.model().n_dof(), block = problem.n_unknowns() / n_dof;  // [q0_j, a_j, b_j]
    Eigen::VectorXd theta = Eigen::VectorXd::Zero(problem.n_unknowns());
    for (int j = 0; j < n_dof; ++j) theta[j * block] = no_home->first[j];
    DesignResult result(problem.Trajectory(theta), problem.Trajectory(theta));
    result.infeasibility = std::move(no_home->second);
    result.status = internal::InfeasibilityStatus(result.infeasibility);
    result.check = result.infeasibility.check;
    result.home = no_home->first;
    result.home_source = home_source;
    result.ramp_seconds = options.ramp_seconds;
    result.initial_value = result.value = std::numeric_limits<double>::quiet_NaN();
    result.wall_seconds = seconds_since_begin();
    return result;
  }

  // The starts run in two rounds when there are several: the first with two
  // thirds of max_evaluations, the second with what each has left. In the
  // second, a start within a factor 2 of the leader's cond (the best after
  // the first round; log 2 of the criterion, every criterion being a log)
  // continues from its own best point; one further behind, or one that
  // stalled twice, or one that found no feasible point, starts again near the
  // leader's best point (its amplitudes perturbed, seeded by the start), so
  // that no start spends its evaluations stuck far above the best (issue 38:
  // the UR10e's starts ended at 5-13x the best). The second round depends
  // only on the first's results: the same for any thread count.
  const bool two_rounds = options.starts > 1;
  const int first_budget = two_rounds ? options.max_evaluations - options.max_evaluations / 3 : options.max_evaluations;
  std::vector<StartRun> runs(static_cast<size_t>(options.starts));
  std::vector<DesignStartSummary> summaries(runs.size());
  std::vector<internal::StartPlan> plans(runs.size());
  std::vector<Eigen::VectorXd> plan_from(runs.size());
  auto run_round = [&](std::vector<StartRun>* round_runs, std::vector<DesignStartSummary>* round_summaries) {
    std::atomic<int> next{0};
    auto worker = [&]() {
      for (int s = next++; s < options.starts; s = next++) {
        const size_t i = static_cast<size_t>(s);
        if (plans[i].budget < 1) continue;  // nothing left for a second round
        internal::RunStart(s, regressor, limits, options, control, problem, lower, upper, t_begin, plans[i],
                           &(*round_runs)[i], &(*round_summaries)[i]);
      }
    };
    std::vector<std::thread> pool;
    const int n_threads = std::min(options.threads, options.starts);
    for (int i = 1; i < n_threads; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  };
  for (internal::StartPlan& plan : plans) plan.budget = first_budget, plan.defer_stall = two_rounds;
  run_round(&runs, &summaries);
  if (two_rounds && !(control.stop && control.stop->load())) {
    int leader = -1;
    for (int s = 0; s < options.starts; ++s) {
      const StartRun& run = runs[static_cast<size_t>(s)];
      if (run.best_theta.size() > 0 && (leader < 0 || run.best_value < runs[static_cast<size_t>(leader)].best_value)) leader = s;
    }
    std::vector<int> restarted_from(runs.size(), -1);
    for (int s = 0; s < options.starts; ++s) {
      const size_t i = static_cast<size_t>(s);
      const StartRun& run = runs[i];
      plans[i].budget = options.max_evaluations - summaries[i].evaluations;
      plans[i].defer_stall = false;
      plans[i].evaluations_before = summaries[i].evaluations, plans[i].best_before = run.best_value;
      const bool behind = leader >= 0 && s != leader &&
                          (run.best_theta.size() == 0 || run.deferred ||
                           run.best_value > runs[static_cast<size_t>(leader)].best_value + std::log(2.0));
      if (behind) {
        // The leader's point, each amplitude coefficient scaled by 1 + 0.03 ξ (ξ ~ N(0, 1)).
        std::mt19937_64 rng(options.seed + 7919u * static_cast<unsigned>(s + 1));
        std::normal_distribution<double> normal(0.0, 1.0);
        plan_from[i] = runs[static_cast<size_t>(leader)].best_theta;
        for (int j = 0; j < problem.n_dof(); ++j) {
          for (int c = 1; c < problem.block(); ++c) plan_from[i][j * problem.block() + c] *= 1.0 + 0.03 * normal(rng);
        }
        restarted_from[i] = leader;
      } else {
        plan_from[i] = run.best_theta.size() > 0 ? run.best_theta : run.last_theta;
      }
      plans[i].from = &plan_from[i];
    }
    std::vector<StartRun> second(runs.size());
    std::vector<DesignStartSummary> second_summaries(runs.size());
    run_round(&second, &second_summaries);
    // Each start's record: the better of its two rounds' points, evaluations summed.
    for (size_t i = 0; i < runs.size(); ++i) {
      if (plans[i].budget < 1) continue;
      StartRun& run = runs[i];
      const StartRun& more = second[i];
      DesignStartSummary& summary = summaries[i];
      const DesignStartSummary& later = second_summaries[i];
      if (more.best_theta.size() > 0 && !(more.best_value >= run.best_value)) {
        run.best_value = more.best_value, run.best_theta = more.best_theta;
      }
      run.last_theta = more.last_theta;
      if (summary.feasible_at < 0 && later.feasible_at >= 0) summary.feasible_at = summary.evaluations + later.feasible_at;
      summary.evaluations += later.evaluations;
      run.evaluations = summary.evaluations;
      summary.best_value = run.best_value;
      summary.status = later.status;
      summary.final_violation = later.final_violation;
      const std::string first_story = summary.outcome;
      internal::DescribeProgress(&summary);
      summary.outcome = first_story;
      if (restarted_from[i] >= 0) summary.outcome += Format("; then from near start %g's best: ", restarted_from[i] + 1) + later.outcome;
    }
  }

  // The starts feasible on the grid, best first; ties go to the lower index
  // (deterministic).
  std::vector<int> ranked;
  for (int s = 0; s < options.starts; ++s) {
    if (runs[static_cast<size_t>(s)].best_theta.size() > 0) ranked.push_back(s);
  }
  if (ranked.empty()) {
    DesignResult result = internal::ExplainNoFeasibleStart(regressor.model(), limits, options, problem, summaries, &runs);
    result.starts = summaries;
    result.home = problem.home();
    result.home_source = home_source;
    result.ramp_seconds = options.ramp_seconds;
    for (const DesignStartSummary& s : summaries) result.evaluations += s.evaluations;
    result.initial_value = result.value = std::numeric_limits<double>::quiet_NaN();
    result.stopped = control.stop && control.stop->load();
    result.wall_seconds = seconds_since_begin();
    return result;
  }
  std::stable_sort(ranked.begin(), ranked.end(), [&](int a, int b) {
    return runs[static_cast<size_t>(a)].best_value < runs[static_cast<size_t>(b)].best_value;
  });
  // The winner: the best whose motion also meets every limit at the check
  // rate. The grid can miss a pair's dip between its instants when a start's
  // clearance repairs ran out; a lesser start that holds everywhere beats
  // it. When none does, the best on the grid (its check says why it is not usable).
  auto make_result = [&](int s) {
    const StartRun& run = runs[static_cast<size_t>(s)];
    DesignResult r(problem.Trajectory(run.best_theta), problem.Trajectory(run.start_theta));
    r.ramp_seconds = options.ramp_seconds;
    r.home = problem.home();
    r.check = CheckTrajectoryLimits(regressor.model(), limits, r.RobotTrajectory(), options.check_rate_hz,
                                    problem.clearance(), options.actuators);
    return r;
  };
  int best = ranked.front();
  DesignResult result = make_result(best);
  for (size_t k = 1; k < ranked.size() && !result.check.feasible(); ++k) {
    DesignResult next = make_result(ranked[k]);
    if (next.check.feasible()) best = ranked[k], result = std::move(next);
  }
  const StartRun& winner = runs[static_cast<size_t>(best)];
  result.starts = summaries;
  result.home = problem.home();
  result.home_source = home_source;
  for (const DesignStartSummary& s : summaries) result.evaluations += s.evaluations;
  result.initial_value = summaries[static_cast<size_t>(best)].initial_value;
  result.value = winner.best_value;
  const std::vector<double> times = DesignSampleTimes(options);
  result.initial = ComputeIdentifiability(regressor.Stack(result.initial_trajectory, times), options.given);
  const Eigen::MatrixXd W = regressor.Stack(result.trajectory, times);
  result.final = ComputeIdentifiability(W, options.given);  // with given motions: the union's
  if (result.final.rank < regressor.n_parameters()) {  // feasible, but the limits leave parameters unexcited
    result.status = DesignStatus::kNotExcited;
    result.infeasibility = internal::ExplainUnexcited(regressor, W, result.final.rank, winner.held_still, result.check);
  }
  result.stopped = control.stop && control.stop->load();
  result.wall_seconds = seconds_since_begin();
  return result;
}

}  // namespace idbench
