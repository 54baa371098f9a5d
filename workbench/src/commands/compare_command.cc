#include "idbench/workbench/commands/compare_command.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/engine/simulation.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/excitation/recorded_motion.h"
#include "idbench/ident/least_squares.h"
#include "idbench/ident/per_body_identifier.h"
#include "idbench/workbench/formats/limits_file.h"
#include "idbench/workbench/formats/scene_file.h"
#include "idbench/workbench/commands/montecarlo_command.h"
#include "number_format.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench {
namespace {

constexpr double kCheckRateHz = 1000.0;
// A true parameter value at most this fraction of the largest is zero up to
// rounding: no %σ (a ratio to ~0), σ itself instead.
constexpr double kZeroValue = 1e-9;

// W of the regressor at the states of a joint log (what Bullet executed).
Eigen::MatrixXd StackStates(const DesignRegressor& regressor, const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd,
                            const Eigen::MatrixXd& qdd) {
  DesignRegressor::Workspace ws(regressor.model());
  const int r = regressor.rows_per_sample();
  Eigen::MatrixXd W(r * q.rows(), regressor.n_parameters());
  JointState x(static_cast<int>(q.cols()));
  for (Eigen::Index s = 0; s < q.rows(); ++s) {
    x.q = q.row(s).transpose();
    x.qd = qd.row(s).transpose();
    x.qdd = qdd.row(s).transpose();
    regressor.Rows(x, &ws, W.middleRows(r * s, r));
  }
  return W;
}

// Per-body Monte-Carlo: Bullet's hinge wrenches at the sample steps plus
// seeded noise, identified per body; mean over trials of the mean relative
// error of every identifiable mass and principal moment.
void PerBodyMonteCarlo(const RobotModel& model, const Trajectory& motion, const CompareOptions& options,
                       const DesignRegressor& regressor, MotionComparison* row) {
  SimulationOptions sim;
  sim.dt = options.dt;
  sim.duration = motion.duration();
  const SimulationLog full = Simulate(model, motion, sim);
  SimulationLog sampled;
  sampled.robot = full.robot;
  sampled.dt = full.dt;
  const double spacing = motion.duration() / options.samples;
  for (int k = 0; k < options.samples; ++k) {
    const int step = full.StepAt(k * spacing);
    if (step >= 0) sampled.steps.push_back(full.steps[static_cast<size_t>(step)]);
  }
  const int n = static_cast<int>(sampled.steps.size());
  Eigen::MatrixXd q(n, model.n_dof()), qd(n, model.n_dof()), qdd(n, model.n_dof());
  for (int s = 0; s < n; ++s) {
    q.row(s) = sampled.steps[static_cast<size_t>(s)].q.transpose();
    qd.row(s) = sampled.steps[static_cast<size_t>(s)].qd.transpose();
    qdd.row(s) = sampled.steps[static_cast<size_t>(s)].qdd.transpose();
  }
  row->realised = ComputeIdentifiability(StackStates(regressor, q, qd, qdd));
  std::vector<int> steps(static_cast<size_t>(n));
  for (int s = 0; s < n; ++s) steps[static_cast<size_t>(s)] = s;
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double sigma_f = options.wrench_noise[0], sigma_m = options.wrench_noise[1];
  for (int trial = 0; trial < options.trials; ++trial) {
    SimulationLog noisy = sampled;
    for (LogStep& step : noisy.steps) {
      for (HingeWrench& h : step.hinge) {
        for (int a = 0; a < 3; ++a) h.f_W[a] += sigma_f * normal(rng), h.m_Bo_W[a] += sigma_m * normal(rng);
      }
    }
    const PerBodyIdentificationResult result = IdentifyPerBody(model, noisy, steps);
    double sum = 0.0;
    int count = 0;
    for (const BodyResult& body : result.bodies) {
      for (const ParameterResult& p : body.parameters) {
        if (!p.identifiable || p.name.rfind("m_e", 0) == 0) continue;  // m and J11..J33
        sum += p.rel_error;
        ++count;
      }
    }
    row->mean_relative_error += count > 0 ? sum / count / options.trials : 0.0;
  }
}

// A motion compare can simulate: at most SimulationOptions::kMaxSteps steps
// of dt, and samples that fall on whole steps (the log rate samples/duration
// divides the simulation rate 1/dt). Throws std::invalid_argument naming the
// motion, the option and values that would work.
void CheckCompareMotion(const std::string& name, double duration, const CompareOptions& options) {
  const double steps = duration / options.dt;
  if (!std::isfinite(duration) || !(steps <= SimulationOptions::kMaxSteps)) {
    throw std::invalid_argument(name + ": lasts " + Shortest(duration) + " s; compare simulates at most " +
                                Shortest(SimulationOptions::kMaxSteps * options.dt) + " s (" +
                                std::to_string(std::lround(SimulationOptions::kMaxSteps)) + " steps of " +
                                Shortest(options.dt) + " s)");
  }
  const double per_sample = steps / options.samples;  // simulation steps between samples
  if (per_sample >= 1.0 - 1e-9 && std::abs(per_sample - std::round(per_sample)) <= 1e-6 * per_sample) return;
  // The nearest sample counts that divide the steps: one below, one above.
  const long n_steps = std::lround(steps);
  long below = 0, above = 0;
  for (long s = std::min<long>(options.samples, n_steps); s >= 1 && below == 0; --s) {
    if (n_steps % s == 0) below = s;
  }
  for (long s = options.samples; s <= n_steps && above == 0; ++s) {
    if (n_steps % s == 0) above = s;
  }
  std::string works = below > 0 ? std::to_string(below) : "";
  if (above > 0 && above != below) works += (works.empty() ? "" : " or ") + std::to_string(above);
  throw std::invalid_argument(
      "samples: " + std::to_string(options.samples) + " samples over " + name + "'s " + Shortest(duration) +
      " s fall every " + Format("%.4g", per_sample) + " simulation steps of " + Shortest(options.dt) +
      " s; they must fall on whole steps (samples must divide the " + std::to_string(n_steps) + " steps)" +
      (works.empty() ? "" : ": `samples` " + works + " would"));
}

// %σ from σ where the true value is not zero up to rounding (kZeroValue);
// there σ itself (FormatCompareTable). The same for every motion.
void SetPredictedSigma(const Eigen::VectorXd& sigma, const Eigen::VectorXd& beta_true, MotionComparison* row) {
  row->predicted_sigma = sigma;
  row->predicted_percent_sigma = 100.0 * sigma.cwiseQuotient(beta_true.cwiseAbs());
  const double largest = beta_true.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < beta_true.size(); ++k) {
    if (std::abs(beta_true[k]) <= kZeroValue * largest) {
      row->predicted_percent_sigma[k] = std::numeric_limits<double>::quiet_NaN();
    }
  }
}

// σ per parameter of weighted least squares on W (full column rank) with
// the known noise σ_j on joint j's rows (rows interleaved by joint):
// √diag((WᵀΣ⁻¹W)⁻¹), what a recorded motion predicts without simulation.
Eigen::VectorXd KnownNoiseSigma(const Eigen::MatrixXd& W, const std::vector<double>& tau_noise, int n_dof) {
  Eigen::MatrixXd Ww = W;
  for (Eigen::Index r = 0; r < Ww.rows(); ++r) {
    Ww.row(r) /= tau_noise.size() == 1 ? tau_noise[0] : tau_noise[static_cast<size_t>(r % n_dof)];
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Ww);
  const Eigen::Index p = W.cols();
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  return R_inv.rowwise().norm();  // cov = R⁻¹R⁻ᵀ
}

// Reads a recorded log with PrepareJointLog (identify's reading, resampling
// and zero-phase filter) as the motion it ran (MakeRecordedMotion); the
// reading's notes and warnings go to report's.
std::unique_ptr<RecordedMotion> LoadRecordedMotion(const std::string& path, const RobotModel& model,
                                                   const CompareOptions& options, CompareReport* report) {
  const PreparedLog prepared = PrepareJointLog(path, model, options.preparation());
  report->notes.insert(report->notes.end(), prepared.notes.begin(), prepared.notes.end());
  report->warnings.insert(report->warnings.end(), prepared.warnings.begin(), prepared.warnings.end());
  return MakeRecordedMotion(prepared, path);
}

// "compare: torque model, 40 parameters, ..." without its newline.
std::string Headline(const CompareReport& report) {
  char line[512];
  std::snprintf(line, sizeof line, "compare: %s model, %zu parameters, %d samples per motion, %d noisy trials",
                std::string(kIdentificationModelNames.Name(report.model)).c_str(), report.parameter_names.size(),
                report.samples, report.trials);
  return line;
}

}  // namespace

LogPreparationOptions CompareOptions::preparation() const {
  LogPreparationOptions out;
  out.format = format;
  out.filter = filter;
  out.max_gap_s = max_gap_s;
  return out;
}

bool CompareOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (trajectories.empty() && logs.empty()) {
    return fail("give at least one motion (built-in name, .json/.csv trajectory file, or a recorded log)");
  }
  if ((!logs.empty() || !given.empty()) && !preparation().IsValid(why)) return false;
  if (static_cast<int>(given.size()) > DesignCommandOptions::kMaxGiven) {
    return fail("given: expected at most " + std::to_string(DesignCommandOptions::kMaxGiven) + " motions, got " +
                std::to_string(given.size()));
  }
  if (!given.empty() && model != IdentificationModel::kJointTorque) {
    return fail("given: motions already recorded enter the joint-torque model's ranking only (model torque), got "
                "model per-body");
  }
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  if (samples < 4) return fail("samples: must be >= 4, got " + std::to_string(samples));
  if (trials < 2 || trials > kMaxTrials) {
    return fail("trials: must be in [2, " + std::to_string(kMaxTrials) + "], got " + std::to_string(trials));
  }
  const double max_duration = SimulationOptions::kMaxSteps * dt;  // [s] what one simulation holds
  if (!(duration > 0.0) || !(duration <= max_duration)) {
    return fail("duration: must be in (0, " + Shortest(max_duration) + "] s (the simulation keeps at most " +
                std::to_string(std::lround(SimulationOptions::kMaxSteps)) + " steps of " + Shortest(dt) + " s), got " + Shortest(duration));
  }
  for (double s : tau_noise) {
    if (!(s > 0.0) || !std::isfinite(s)) return fail("tau_noise: every value must be > 0 N m");
  }
  if (wrench_noise.size() != 2 || !(wrench_noise[0] > 0.0) || !(wrench_noise[1] > 0.0)) {
    return fail("wrench_noise: give force and moment sigma, both > 0 (N, N m)");
  }
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  return true;
}

namespace {

// The options with every recorded log among the motions moved to `logs`: a
// CSV with torque or current columns, a bag or a log description given where
// a motion is expected is compared as what it is (IsRecordedJointLogPath).
CompareOptions WithRecordedLogsAsLogs(const CompareOptions& given) {
  CompareOptions options = given;
  options.trajectories.clear();
  options.logs.clear();
  for (const std::string& name : given.trajectories) {
    (IsRecordedJointLogPath(name) ? options.logs : options.trajectories).push_back(name);
  }
  options.logs.insert(options.logs.end(), given.logs.begin(), given.logs.end());
  return options;
}

}  // namespace

CompareReport RunCompare(const RobotModel& loaded, const CompareOptions& given) {
  const CompareOptions options = WithRecordedLogsAsLogs(given);
  const RobotModel model = MountRobot(loaded, options.base_pose);  // gravity seen from the base
  CheckRegressorSamples("samples", options.samples, model.n_dof());
  const bool per_body = options.model == IdentificationModel::kPerBody;
  const DesignRegressor regressor = per_body ? DesignRegressor::PerBody(model)
                                             : DesignRegressor::JointTorque(model, *ParseFrictionTerms(options.friction, nullptr));
  CompareReport report;
  report.model = options.model;
  report.samples = options.samples;
  report.trials = options.trials;
  report.parameter_names = regressor.parameter_names();
  report.true_parameters = regressor.true_parameters();
  const std::vector<JointLimits> limits = RobotLimits(model);
  std::optional<ClearanceModel> clearance;
  if (options.clearance >= 0.0) {
    clearance.emplace(model, options.clearance, options.scene.empty() ? Cell() : ReadSceneFile(options.scene),
                      options.base_pose);
  }
  const BuiltinMotionOptions builtin{.duration = options.duration, .paper_qdd = 0.5};
  // Every motion read and checked before any work: a designed motion's
  // duration fits one simulation, and its samples fall on whole simulation
  // steps; a recorded log is read whole (not simulated).
  if (!per_body) report.tau_noise = TorqueNoiseOrDefault(options.tau_noise, model.n_dof());
  std::vector<std::string> names = options.trajectories;
  std::vector<std::unique_ptr<Trajectory>> motions;
  for (const std::string& name : options.trajectories) {
    motions.push_back(LoadTrajectoryArg(name, model, builtin));
    CheckCompareMotion(name, motions.back()->duration(), options);
  }
  // A recorded log is simulated like a designed motion over its span cut to
  // a whole number of sample spacings (samples·dt: the instants fall on whole
  // steps); not when shorter than one spacing or longer than one simulation.
  std::vector<bool> simulated(options.trajectories.size(), true);
  const double spacing = options.samples * options.dt;
  for (const std::string& path : options.logs) {
    names.push_back(path);
    std::unique_ptr<RecordedMotion> motion = LoadRecordedMotion(path, model, options, &report);
    const double cut = std::floor(motion->duration() / spacing + 1e-9) * spacing;
    simulated.push_back(cut >= spacing && cut / options.dt <= SimulationOptions::kMaxSteps);
    if (simulated.back()) motion->Cut(cut);
    motions.push_back(std::move(motion));
  }
  // The given motions' information, at one row per second (scaled to each
  // candidate's rows per second below).
  GivenInformation given_per_second;
  if (!options.given.empty()) {
    given_per_second = ReadGivenInformation(model, regressor, options.given, options.preparation(), 1.0, nullptr,
                                            &report.notes);
    report.ranked_with_given = true;
  }
  for (size_t m = 0; m < names.size(); ++m) {
    const std::string& name = names[m];
    const std::unique_ptr<Trajectory>& motion = motions[m];
    MotionComparison row;
    row.name = name;
    row.recorded = m >= options.trajectories.size();
    row.simulated = simulated[m];
    row.duration = motion->duration();
    // Designed and recorded alike: W on `samples` instants over the motion.
    std::vector<double> times;
    for (int k = 0; k < options.samples; ++k) times.push_back(k * motion->duration() / options.samples);
    const Eigen::MatrixXd W = regressor.Stack(*motion, times);
    row.designed = ComputeIdentifiability(W);
    if (!given_per_second.empty()) {
      row.with_given = ComputeIdentifiability(W, given_per_second.Scaled(options.samples / motion->duration()));
    }
    row.limits = CheckTrajectoryLimits(model, limits, *motion, kCheckRateHz, clearance ? &*clearance : nullptr);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (row.designed.rank < regressor.n_parameters()) {
      const LeastSquaresSolution ls =
          SolveLeastSquares(W, Eigen::VectorXd::Zero(W.rows()), regressor.parameter_names());
      for (size_t i = 0; i < ls.identifiable.size(); ++i) {
        if (!ls.identifiable[i]) row.unexcited.push_back(regressor.parameter_names()[i]);
      }
      row.realised.cond = row.mean_relative_error = nan;
      row.predicted_percent_sigma = Eigen::VectorXd::Constant(regressor.n_parameters(), nan);
    } else if (!row.simulated) {
      // Not simulated: no realised states, no Monte-Carlo error; %σ from the
      // recorded states with the torque noise (torque model).
      row.realised.cond = row.mean_relative_error = nan;
      if (!per_body) SetPredictedSigma(KnownNoiseSigma(W, report.tau_noise, model.n_dof()), report.true_parameters, &row);
    } else if (per_body) {
      PerBodyMonteCarlo(model, *motion, options, regressor, &row);
    } else {
      MonteCarloOptions mc;
      mc.trajectory = name;
      mc.duration = options.duration;
      mc.dt = options.dt;
      mc.samples = options.samples;
      mc.tau_noise = report.tau_noise;
      mc.friction = options.friction;
      mc.trials = options.trials;
      mc.seed = options.seed;
      const MonteCarloReport r = RunMonteCarlo(model, mc, *motion);
      // W of the motion had full rank, that of its simulated states not: the motion is wrong input.
      // A recorded log's reading warnings may say why ("is the log in radians?"): with the error, not lost.
      if (r.status == MonteCarloStatus::kNotExcited) {
        std::string message = r.message;
        for (const std::string& warning : report.warnings) message += "\n  " + warning;
        throw std::invalid_argument(message);
      }
      row.realised = ComputeIdentifiability(StackStates(regressor, r.log.q, r.log.qd, r.log.qdd));
      SetPredictedSigma(r.predicted_sigma, r.beta_true, &row);
      row.mean_relative_error = r.mean_relative_error;
    }
    report.motions.push_back(std::move(row));
  }
  // Ranked by cond(W), designed and recorded together (with given motions:
  // of each one's union with them); rank-deficient last (0).
  const auto ranked = [&](const MotionComparison& m) -> const Identifiability& {
    return report.ranked_with_given ? m.with_given : m.designed;
  };
  std::vector<size_t> order;
  for (size_t m = 0; m < report.motions.size(); ++m) {
    const MotionComparison& row = report.motions[m];
    if (report.ranked_with_given ? row.with_given.rank == row.with_given.cols : row.unexcited.empty()) {
      order.push_back(m);
    }
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return ranked(report.motions[a]).cond < ranked(report.motions[b]).cond;
  });
  for (size_t i = 0; i < order.size(); ++i) report.motions[order[i]].rank = static_cast<int>(i + 1);
  // The verdict: limits first (a motion the robot must not run), then excitation.
  const auto any = [&](auto failed) { return std::any_of(report.motions.begin(), report.motions.end(), failed); };
  if (any([](const MotionComparison& m) { return !m.limits.feasible(); })) {
    report.status = CompareStatus::kOutsideLimits;
  } else if (any([](const MotionComparison& m) { return !m.unexcited.empty(); })) {
    report.status = CompareStatus::kNotExcited;
  }
  return report;
}

std::string CompareReport::BriefReport() const {
  std::string out = Headline(*this) + "\n";
  std::string outside, unexcited;  // the motions' names, comma-separated
  for (const MotionComparison& m : motions) {
    if (m.rank == 1) {
      out += "best: " + m.name + " (cond(W) " + Format("%.5g", m.designed.cond) + ", MC error " +
             Format("%.4g", m.mean_relative_error) + ")\n";
    }
    if (!m.limits.feasible()) outside += (outside.empty() ? "" : ", ") + m.name;
    if (!m.unexcited.empty()) unexcited += (unexcited.empty() ? "" : ", ") + m.name;
  }
  if (!outside.empty()) out += "outside the limits: " + outside + "\n";
  if (!unexcited.empty()) out += "not exciting every parameter: " + unexcited + "\n";
  return out + std::string(kCompareStatusNames.Name(status)) + "\n";
}

std::string FormatCompareTable(const CompareOptions& options, const CompareReport& report) {
  std::string out;
  for (const std::string& note : report.notes) out += note + "\n";  // as identify's table starts
  char line[512];
  out += Headline(report) + "\n\n";
  std::snprintf(line, sizeof line, "%4s %-28s %11s %11s %11s %11s %11s %11s  %s\n", "rank", "motion", "cond(W)",
                "norm cond", "log det", "sigma_min", "realised", "MC error", "limits, clearance");
  out += line;
  bool any_recorded = false;
  // A motion's name in a 28-column field: its end.
  const auto short_name = [](const std::string& name) {
    return name.size() > 28 ? "…" + name.substr(name.size() - 26) : name;
  };
  for (const MotionComparison& m : report.motions) {
    std::string name = short_name(m.name);
    any_recorded = any_recorded || !m.simulated;
    // A recorded log not simulated: "—" and the footnote below.
    const std::string realised = !m.simulated ? "—¹" : Format("%.5g", m.realised.cond);
    const std::string mc = !m.simulated ? "—¹" : Format("%.4g", m.mean_relative_error);
    std::snprintf(line, sizeof line, "%4s %-28s %11s %11s %11s %11s %*s %*s  %s\n",
                  m.rank > 0 ? std::to_string(m.rank).c_str() : "-", name.c_str(),
                  Format("%.5g", m.designed.cond).c_str(), Format("%.5g", m.designed.cond_normalised).c_str(),
                  Format("%.5g", m.designed.log_det).c_str(), Format("%.5g", m.designed.sigma_min).c_str(),
                  m.simulated ? 11 : 14, realised.c_str(), m.simulated ? 11 : 14, mc.c_str(),  // "—¹": 5 bytes, 2 columns
                  m.limits.feasible() ? "within" : "VIOLATED");
    out += line;
  }
  std::string cell;  // how close each motion comes to the cell (floor, obstacles)
  for (const MotionComparison& m : report.motions) {
    if (const std::string closest = m.limits.ClosestObstacleLine(); !closest.empty()) {
      cell += "  " + m.name + ": " + closest + "\n";
    }
  }
  if (!cell.empty()) out += "\nclearance to the cell, per motion:\n" + cell;
  if (report.ranked_with_given) {
    out += "\nwith the given motions (";
    for (size_t i = 0; i < options.given.size(); ++i) out += (i ? ", " : "") + options.given[i];
    out += "), cond(W) of each motion's union with them, a given second weighed as a second of the motion:\n";
    for (const MotionComparison& m : report.motions) {
      std::snprintf(line, sizeof line, "%4s %-28s %11s\n", m.rank > 0 ? std::to_string(m.rank).c_str() : "-",
                    short_name(m.name).c_str(), Format("%.5g", m.with_given.cond).c_str());
      out += line;
    }
    out += "\nrank: by cond(W) of each motion's union with the given motions (1: lowest).";
  } else {
    out += "\nrank: by cond(W), designed and recorded motions together (1: lowest).";
  }
  if (any_recorded) {
    out += "\n¹ a recorded log shorter than samples x dt or longer than one simulation: not simulated, so no realised "
           "cond or Monte-Carlo error; its cond, log det and %sigma are of the recorded states, %sigma with the "
           "torque noise.";
  }
  out += "\n";
  out += options.model == IdentificationModel::kJointTorque
             ? "\nMC error: mean over trials of |beta_hat - beta|/|beta| (WLS, torque noise); realised: cond(W) of the "
               "states Bullet executed.\n"
             : "\nMC error: mean over trials of the mean relative error of every identifiable mass and principal "
               "moment (hinge-wrench noise); realised: cond(W) of the states Bullet executed.\n";
  if (options.model == IdentificationModel::kJointTorque) {
    out += "\npredicted %sigma per base parameter:\n";
    std::snprintf(line, sizeof line, "%4s", "#");
    out += line;
    for (size_t m = 0; m < report.motions.size(); ++m) {
      std::snprintf(line, sizeof line, " %11s", ("T" + std::to_string(m + 1)).c_str());
      out += line;
    }
    out += "  parameter   (s=…: sigma itself, in the parameter's unit, where its true value is zero)\n";
    for (size_t k = 0; k < report.parameter_names.size(); ++k) {
      std::snprintf(line, sizeof line, "%4zu", k + 1);
      out += line;
      for (const MotionComparison& m : report.motions) {
        const Eigen::Index i = static_cast<Eigen::Index>(k);
        const bool zero = m.unexcited.empty() && m.predicted_sigma.size() > i && std::isnan(m.predicted_percent_sigma[i]);
        std::snprintf(line, sizeof line, " %11s",
                      (zero ? Format("s=%.3g", m.predicted_sigma[i]) : Format("%.4g", m.predicted_percent_sigma[i])).c_str());
        out += line;
      }
      out += "  " + report.parameter_names[k] + "\n";
    }
  }
  for (const MotionComparison& m : report.motions) {
    if (!m.unexcited.empty()) {
      out += "\n" + m.name + " does not excite every parameter (rank " + std::to_string(m.designed.rank) + " of " +
             std::to_string(m.designed.cols) + "): no estimate, so no %sigma or Monte-Carlo error. " +
             std::to_string(m.unexcited.size()) + " parameters are zero or dependent columns of W:\n";
      constexpr size_t kListed = 8;
      for (size_t i = 0; i < std::min(kListed, m.unexcited.size()); ++i) out += "  " + m.unexcited[i] + "\n";
      if (m.unexcited.size() > kListed) {
        out += "  … and " + std::to_string(m.unexcited.size() - kListed) + " more (compare.json: \"unexcited\")\n";
      }
    }
    if (!m.limits.feasible()) {
      out += "\n" + m.name + " violates the robot file's limits or the clearance:\n" + m.limits.Explain();
    }
  }
  return out;
}

std::string FormatCompareJson(const CompareOptions& options, const CompareReport& report) {
  using nlohmann::json;
  json motions = json::array();
  for (const MotionComparison& m : report.motions) {
    json j = {{"trajectory", m.name},
              {"recorded", m.recorded},
              {"simulated", m.simulated},
              {"rank", m.rank > 0 ? json(m.rank) : json(nullptr)},
              {"duration", m.duration},
              {"designed", IdentifiabilityJson(m.designed)},
              {"realised", IdentifiabilityJson(m.realised)},
              {"with_given", report.ranked_with_given ? IdentifiabilityJson(m.with_given) : json(nullptr)},
              {"mean_relative_error", std::isfinite(m.mean_relative_error) ? json(m.mean_relative_error) : json(nullptr)},
              {"unexcited", m.unexcited},
              {"within_robot_limits", m.limits.feasible()},
              {"limit_violations", m.limits.Explain()}};
    if (const ConstraintMargin* c = m.limits.ClosestObstacle()) {
      j["closest_obstacle"] = {{"obstacle", c->obstacle}, {"link", c->link}, {"distance", c->value},
                               {"time", c->time}, {"minimum", c->limit}};
    }
    if (m.predicted_percent_sigma.size() > 0 && m.unexcited.empty()) {
      json percent = json::array();  // null where the true value is zero: see predicted_sigma
      for (Eigen::Index k = 0; k < m.predicted_percent_sigma.size(); ++k) {
        percent.push_back(std::isnan(m.predicted_percent_sigma[k]) ? json(nullptr) : json(m.predicted_percent_sigma[k]));
      }
      j["predicted_percent_sigma"] = percent;
      j["predicted_sigma"] = ToStdVector(m.predicted_sigma);
    }
    motions.push_back(j);
  }
  const json doc = {{"command", options.command_line},
                    {"robot", options.robot},
                    {"model", std::string(kIdentificationModelNames.Name(options.model))},
                    {"samples", options.samples},
                    {"trials", options.trials},
                    {"seed", options.seed},
                    {"scene", options.scene.empty() ? json(nullptr) : json(options.scene)},
                    {"base_pose", options.base_pose.xyz_rpy},
                    {"noise", options.model == IdentificationModel::kJointTorque ? json{{"tau", report.tau_noise}}
                                                        : json{{"force", options.wrench_noise[0]},
                                                               {"moment", options.wrench_noise[1]}}},
                    {"given", options.given},
                    {"parameters", report.parameter_names},
                    {"true_parameters", ToStdVector(report.true_parameters)},
                    {"motions", motions}};
  return doc.dump(2) + "\n";
}

std::string FormatCompareCsv(const CompareReport& report) {
  std::string out = "trajectory,duration,cond,cond_normalised,log_det,sigma_min,realised_cond,mean_relative_error,"
                    "within_robot_limits,recorded,rank\n";
  for (const MotionComparison& m : report.motions) {
    for (double v : {m.duration, m.designed.cond, m.designed.cond_normalised, m.designed.log_det,
                     m.designed.sigma_min, m.realised.cond, m.mean_relative_error}) {
      if (out.back() != '\n') out += ",";
      else out += "\"" + m.name + "\",";
      AppendShortest(&out, v);
    }
    out += m.limits.feasible() ? ",1," : ",0,";
    out += (m.recorded ? "1," : "0,") + std::to_string(m.rank) + "\n";
  }
  return out;
}

}  // namespace idbench
