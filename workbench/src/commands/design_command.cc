#include "idbench/workbench/commands/design_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include "idbench/logs/open_joint_log.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/ident/prepared_log_equations.h"
#include "idbench/ident/linear_estimator.h"
#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/workbench/formats/limits_file.h"
#include "idbench/workbench/formats/scene_file.h"
#include "idbench/workbench/formats/trajectory_file.h"
#include "idbench/workbench/formats/transmission_file.h"
#include "number_format.h"

namespace idbench {
namespace {

bool IsCondCriterion(DesignCriterion c) {
  return c == DesignCriterion::kLogCond || c == DesignCriterion::kLogCondNormalised;
}

// "cond 42.1" for the condition-number criteria, else the criterion value.
std::string CriterionText(DesignCriterion c, double value) {
  char buf[96];
  if (!std::isfinite(value)) return "none feasible yet";
  if (IsCondCriterion(c)) std::snprintf(buf, sizeof buf, "%s %.4g", c == DesignCriterion::kLogCond ? "cond" : "normalised cond", std::exp(value));
  else std::snprintf(buf, sizeof buf, "%s %.6g", DesignCriterionName(c).c_str(), value);
  return buf;
}

}  // namespace

bool DesignCommandOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  std::string friction_why;
  if (!ParseFrictionTerms(friction, &friction_why)) return fail("friction: " + friction_why);
  if (!design.IsValid(why)) return false;
  if (!(csv_rate_hz > 0.0) || !std::isfinite(csv_rate_hz)) return fail("csv_rate_hz: must be > 0 Hz");
  if (csv_rate_hz < MinimumCsvRate(design)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "csv_rate_hz: %g Hz cannot sample the motion; trajectory.csv needs at least 10 samples per period of "
                  "the highest harmonic, 10 x %d harmonics x %g Hz (f0) = %g Hz",
                  csv_rate_hz, design.harmonics, design.f0, MinimumCsvRate(design));
    return fail(buf);
  }
  for (double q : home) {
    if (!std::isfinite(q)) return fail("home: expected finite joint angles [rad]");
  }
  if (std::string out_why; !IsUsableOutputDirectory(out_dir, "out_dir", &out_why)) return fail(out_why);
  if (static_cast<int>(given.size()) > kMaxGiven) {
    return fail("given: expected at most " + std::to_string(kMaxGiven) + " motions, got " + std::to_string(given.size()));
  }
  if (!given.empty() && model != IdentificationModel::kJointTorque) {
    return fail("given: motions already recorded enter the joint-torque model's criterion only (model torque), got "
                "model per-body");
  }
  for (const std::string& g : given) {
    if (g.empty()) return fail("given: an empty path");
  }
  if (!given.empty() && !given_reading.IsValid(why)) return false;
  return true;
}

GivenInformation ReadGivenInformation(const RobotModel& model, const DesignRegressor& regressor,
                                      const std::vector<std::string>& paths, const LogPreparationOptions& reading,
                                      double rows_per_second, std::vector<DesignCommandReport::GivenMotion>* motions,
                                      std::vector<std::string>* notes) {
  if (!(rows_per_second > 0.0) || !std::isfinite(rows_per_second)) {
    throw std::invalid_argument("given: expected the new motion's samples per second > 0, got " +
                                Format("%g", rows_per_second));
  }
  const int n_dof = model.n_dof();
  std::vector<Eigen::MatrixXd> factors;
  std::vector<double> weights, rows;
  std::vector<bool> measured;
  for (const std::string& path : paths) {
    DesignCommandReport::GivenMotion motion;
    motion.path = path;
    // A designed trajectory (.json or .csv, not what a robot recorded: no
    // torque columns) unless the columns are named for a log.
    if (IsTrajectoryFile(path) && !IsRecordedJointLogPath(path) && reading.format.columns.empty()) {
      // A designed motion: its rows at kGivenTrajectoryRateHz, no torques.
      const std::unique_ptr<Trajectory> trajectory = LoadTrajectoryArg(path, model, {});
      motion.measured = false;
      motion.duration_s = trajectory->duration();
      const double n_real = std::floor(motion.duration_s * kGivenTrajectoryRateHz);
      if (!(n_real <= static_cast<double>(kMaxGivenTrajectorySamples))) {
        throw std::invalid_argument(path + ": " + Format("%g", motion.duration_s) + " s at " +
                                    Format("%g", kGivenTrajectoryRateHz) + " Hz is more than " +
                                    std::to_string(kMaxGivenTrajectorySamples) + " samples");
      }
      const Eigen::Index n = std::max<Eigen::Index>(static_cast<Eigen::Index>(n_real), 1);
      std::vector<double> times(static_cast<size_t>(n));
      for (Eigen::Index k = 0; k < n; ++k) times[static_cast<size_t>(k)] = static_cast<double>(k) / kGivenTrajectoryRateHz;
      const Eigen::MatrixXd W = regressor.Stack(*trajectory, times);
      if (W.rows() <= W.cols()) {
        throw std::invalid_argument(path + ": " + std::to_string(n) + " samples at " +
                                    Format("%g", kGivenTrajectoryRateHz) + " Hz give " + std::to_string(W.rows()) +
                                    " equations for " + std::to_string(W.cols()) + " base parameters");
      }
      motion.n_samples = n;
      factors.push_back(CombinedFactor(W, Eigen::VectorXd::Zero(W.rows())));
    } else {
      // A recorded log, read as identify reads it; its equations for the
      // regressor's base parameters folded into one factor.
      const PreparedLog log = PrepareJointLog(path, model, reading);
      const StackedFactors folded = FoldPreparedLog(log, model, regressor.friction(), regressor.base());
      motion.n_samples = folded.n_samples();
      motion.duration_s = log.log.t.size() > 1 ? log.log.t[log.log.t.size() - 1] - log.log.t[0] : 0.0;
      if (!(motion.duration_s > 0.0)) throw std::invalid_argument(path + ": the log spans no time");
      factors.push_back(CombinedFactor(folded, Eigen::VectorXd::Ones(n_dof)));
      if (notes) notes->insert(notes->end(), log.notes.begin(), log.notes.end());
    }
    // A second of this motion weighs as a second of the new one.
    motion.weight = rows_per_second * motion.duration_s / static_cast<double>(motion.n_samples);
    weights.push_back(motion.weight);
    rows.push_back(static_cast<double>(motion.n_samples * n_dof));
    measured.push_back(motion.measured);
    if (motions) motions->push_back(motion);
  }
  return GivenInformationFromFactors(factors, weights, rows, measured);
}

double MinimumCsvRate(const DesignOptions& design) { return 10.0 * design.harmonics * design.f0; }

bool DesignCommandOptions::IsValidFor(const RobotModel& robot, std::string* why) const {
  if (home.empty() || static_cast<int>(home.size()) == robot.n_dof()) return true;
  if (why) {
    *why = "home: expected " + std::to_string(robot.n_dof()) + " joint angles (one per joint of " + robot.name() +
           "), got " + std::to_string(home.size());
  }
  return false;
}

DesignOptions DesignCommandOptions::Resolved() const {
  DesignOptions d = design;
  if (!home.empty()) d.home = Eigen::Map<const Eigen::VectorXd>(home.data(), static_cast<Eigen::Index>(home.size()));
  d.check_rate_hz = std::max(d.check_rate_hz, csv_rate_hz);
  d.criterion = criterion                                  ? *criterion
                : model == IdentificationModel::kPerBody ? DesignCriterion::kLogDet
                                                         : DesignCriterion::kLogCond;
  d.algorithm = algorithm;
  return d;
}

DesignRegressor DesignCommandOptions::MakeRegressor(const RobotModel& robot) const {
  if (model == IdentificationModel::kPerBody) return DesignRegressor::PerBody(robot);
  return DesignRegressor::JointTorque(robot, *ParseFrictionTerms(friction, nullptr));
}

std::vector<JointLimits> DesignLimits(const RobotModel& model, const DesignCommandOptions& options) {
  return options.limits.empty() ? RobotLimits(model) : ReadLimitsFile(options.limits, model);
}

ActuatorLimits DesignActuatorLimits(const RobotModel& model, const DesignCommandOptions& options,
                                    const std::optional<Transmission>& from_urdf) {
  ActuatorLimits actuators;
  if (!options.limits.empty()) actuators.motors = ReadActuatorLimitsFile(options.limits);
  if (actuators.empty()) return actuators;
  if (options.transmission.empty()) {
    throw std::invalid_argument("transmission: the limits file's \"actuators\" are motor-side limits and need the "
                                "transmission they act through (\"urdf\" or a transmission file)");
  }
  actuators.transmission = *ReadTransmissionArg(options.transmission, options.robot, model.n_dof(), from_urdf);
  actuators.Check(model.n_dof());
  return actuators;
}

DesignCommandReport RunDesign(const RobotModel& model, const DesignCommandOptions& options,
                              const std::atomic<bool>* stop, const std::optional<Transmission>& from_urdf) {
  DesignControl control;
  control.stop = stop;
  const std::vector<JointLimits> limits = DesignLimits(model, options);
  DesignCommandOptions with_actuators = options;
  with_actuators.design.actuators = DesignActuatorLimits(model, options, from_urdf);
  return RunDesign(model, with_actuators, limits, control);
}

DesignCommandReport RunDesign(const RobotModel& loaded, const DesignCommandOptions& options,
                              const std::vector<JointLimits>& limits, const DesignControl& observer) {
  const RobotModel model = MountRobot(loaded, options.design.base_pose);  // gravity seen from the base
  DesignOptions design = options.Resolved();
  if (!options.scene.empty()) design.scene = ReadSceneFile(options.scene);  // a bad file before anything else
  CheckDesignLimits(model, limits);
  CheckTrajectoryCsvRate(options.design.period_duration(), options.csv_rate_hz, model.n_dof());  // before the design
  const DesignRegressor regressor = options.MakeRegressor(model);
  CheckDesignFitsInMemory(regressor, design);  // before the progress state per start
  // The motions already recorded: the criterion becomes the union's.
  std::vector<DesignCommandReport::GivenMotion> given;
  std::vector<std::string> given_notes;
  if (!options.given.empty()) {
    // The new motion's rows per second: the design's samples over its duration.
    const double rows_per_second = static_cast<double>(design.samples) / design.period_duration();
    design.given = ReadGivenInformation(model, regressor, options.given, options.given_reading, rows_per_second,
                                        &given, &given_notes);
  }

  // Progress: at most one line per start every second.
  std::mutex mutex;
  std::vector<std::chrono::steady_clock::time_point> last(static_cast<size_t>(design.starts));
  DesignControl control;
  control.stop = observer.stop;
  control.progress = observer.progress;
  if (design.clearance >= 0.0) {  // said even when quiet: the design is not protected there
    std::string bare;
    for (const Link& link : model.links()) {
      if (link.CollisionShapes().empty()) bare += (bare.empty() ? "" : ", ") + link.name;
    }
    if (!bare.empty()) {
      std::fprintf(stderr, "idbench: warning: clearance is not checked for links without shapes: %s\n", bare.c_str());
    }
  }
  std::vector<std::string> excluded, held;
  if (design.clearance >= 0.0) {  // the pairs left out and those held at q = 0, named once
    const ClearanceModel clearance(model, design.clearance, design.scene, design.base_pose);
    excluded = clearance.excluded();
    for (const ClearancePair& p : clearance.pairs()) {
      if (p.minimum < clearance.min_clearance()) held.push_back(p.Name(model) + Format(" >= %.4g m", p.minimum));
    }
    if (!options.quiet) {
      std::string line;
      for (const std::string& e : excluded) line += "\n  " + e;
      if (!excluded.empty()) std::fprintf(stderr, "clearance: not checked (joined, in contact by construction or out of reach):%s\n", line.c_str());
      line.clear();
      for (const std::string& h : held) line += "\n  " + h;
      if (!held.empty()) {
        std::fprintf(stderr, "clearance: closer than %g m at q = 0, kept at least as far as there:%s\n",
                     design.clearance, line.c_str());
      }
    }
  }
  if (!options.quiet) {
    std::fprintf(stderr, "design: %s, %s model (%d parameters), %s, %d starts on %d threads, seed %u\n",
                 model.name().c_str(), std::string(kIdentificationModelNames.Name(options.model)).c_str(), regressor.n_parameters(),
                 DesignAlgorithmName(design.algorithm).c_str(), design.starts, std::min(design.threads, design.starts),
                 design.seed);
    control.progress = [&](const DesignProgress& p) {
      if (observer.progress) observer.progress(p);
      const std::lock_guard<std::mutex> lock(mutex);
      const auto now = std::chrono::steady_clock::now();
      auto& t = last[static_cast<size_t>(p.start)];
      if (now - t < std::chrono::seconds(1)) return;
      t = now;
      std::fprintf(stderr, "  start %d/%d: %d evaluations, best %s%s\n", p.start + 1, design.starts, p.evaluations,
                   CriterionText(design.criterion, p.best_value).c_str(), p.feasible ? "" : " (current point infeasible)");
    };
  }
  DesignCommandReport report{limits,   DesignExcitation(regressor, limits, design, control),
                             regressor.parameter_names(), excluded, held, design.actuators, design.criterion};
  if (!design.given.empty()) {
    report.given = std::move(given);
    report.given_notes = std::move(given_notes);
    report.noise_variance = design.given.noise_variance;
    const Eigen::MatrixXd none(0, regressor.n_parameters());
    report.given_alone = ComputeIdentifiability(none, design.given);
    report.sigma_given = PredictedSigma(design.given);
    if (report.status() == DesignStatus::kFeasible || report.status() == DesignStatus::kNotExcited) {
      report.sigma_with_new =
          PredictedSigma(design.given, regressor.Stack(report.result.trajectory, DesignSampleTimes(design)));
    }
  }
  if (report.status() != DesignStatus::kFeasible) return report;  // result.infeasibility says why
  if (!options.quiet) {
    for (size_t s = 0; s < report.result.starts.size(); ++s) {
      const DesignStartSummary& st = report.result.starts[s];
      std::fprintf(stderr, "  start %zu: %s -> %s, %d evaluations (%s): %s\n", s + 1,
                   CriterionText(design.criterion, st.initial_value).c_str(),
                   CriterionText(design.criterion, st.best_value).c_str(), st.evaluations, st.status.c_str(),
                   st.outcome.c_str());
    }
    if (report.result.stopped) std::fprintf(stderr, "design: stopped; keeping the best feasible design so far\n");
  }
  return report;
}

nlohmann::json IdentifiabilityJson(const Identifiability& id) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"cond", number(id.cond)},           {"cond_normalised", number(id.cond_normalised)},
          {"log_det", number(id.log_det)},     {"sigma_min", id.sigma_min},
          {"sigma_max", id.sigma_max},         {"rank", id.rank},
          {"rows", id.rows},                   {"parameters", id.cols}};
}

std::string FormatDesignTrajectoryCsv(const RobotModel& model, const DesignCommandOptions& options,
                                      const DesignCommandReport& report) {
  std::vector<std::string> joint_names;
  for (const Link& link : model.links()) joint_names.push_back(link.joint_name);
  return FormatTrajectoryCsv(report.result.RobotTrajectory(), options.csv_rate_hz, options.csv_columns == TrajectoryCsvColumns::kQQdQdd,
                             joint_names);
}

std::string DesignCommandReport::BriefReport() const {
  const DesignResult& r = result;
  std::string out = "design " + std::string(kDesignStatusNames.Name(r.status)) + ": ";
  if (r.status == DesignStatus::kFeasible) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s -> %s, %s at %g Hz, ", CriterionText(criterion, r.initial_value).c_str(),
                  CriterionText(criterion, r.value).c_str(), r.check.feasible() ? "feasible" : "INFEASIBLE",
                  r.check.rate_hz);
    out += buf;
    out += r.usable() ? "usable" : "not usable: " + r.Rejection();
  } else {
    out += r.Rejection();
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "; %d evaluations in %.2f s%s", r.evaluations, r.wall_seconds,
                r.stopped ? " (stopped)" : "");
  return out + buf;
}

namespace {

// With given motions: what they are, cond alone and with the new motion, and
// the predicted σ table.
std::string FormatGivenSummary(const DesignCommandReport& report) {
  std::string out = "the criterion and the numbers above are of the union of the new motion with the given motions:\n";
  for (const std::string& note : report.given_notes) out += "  " + note + "\n";
  char buf[512];
  for (const DesignCommandReport::GivenMotion& g : report.given) {
    std::snprintf(buf, sizeof buf, "  given %s: %s, %lld samples over %.4g s, each weighted %.4g (a second as a second of the new motion)\n",
                  g.path.c_str(), g.measured ? "recorded log" : "designed trajectory (no torques)",
                  static_cast<long long>(g.n_samples), g.duration_s, g.weight);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "cond(W) of the given motions alone %.6g, with the new motion %.6g\n",
                report.given_alone.cond, report.result.final.cond);
  out += buf;
  if (std::isnan(report.noise_variance)) {
    out += "predicted sigma per base parameter, for a torque noise of 1 N m per sample at the design's rate (no given "
           "log has torques to estimate it):\n";
  } else {
    std::snprintf(buf, sizeof buf, "predicted sigma per base parameter (as if the residual were white; noise s = %.4g N m "
                  "per sample at the design's rate, from the given logs' least-squares residual):\n",
                  std::sqrt(report.noise_variance));
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "%4s  %13s  %15s  %8s  %s\n", "#", "given alone", "with new motion", "ratio",
                "base parameter");
  out += buf;
  for (Eigen::Index k = 0; k < report.sigma_given.size(); ++k) {
    const double alone = report.sigma_given[k];
    const double with_new = k < report.sigma_with_new.size() ? report.sigma_with_new[k] : std::nan("");
    std::snprintf(buf, sizeof buf, "%4lld  %13.4g  %15.4g  %8.3g  %s\n", static_cast<long long>(k + 1), alone,
                  with_new, with_new / alone, report.parameter_names[static_cast<size_t>(k)].c_str());
    out += buf;
  }
  return out;
}

}  // namespace

std::string FormatDesignSummary(const DesignCommandOptions& options, const DesignCommandReport& report) {
  const DesignResult& r = report.result;
  const DesignOptions design = options.Resolved();
  char buf[512];
  std::string out;
  std::snprintf(buf, sizeof buf,
                "criterion %s: %.6g -> %.6g\n"
                "cond(W)            %12.6g -> %-12.6g (never cond(WᵀW))\n"
                "normalised cond    %12.6g -> %-12.6g\n"
                "log det(WᵀW/m)     %12.6g -> %-12.6g\n"
                "sigma_min(W)       %12.6g -> %-12.6g\n"
                "%d evaluations in %.2f s; %s at %g Hz\n",
                DesignCriterionName(design.criterion).c_str(), r.initial_value, r.value, r.initial.cond, r.final.cond,
                r.initial.cond_normalised, r.final.cond_normalised, r.initial.log_det, r.final.log_det,
                r.initial.sigma_min, r.final.sigma_min, r.evaluations, r.wall_seconds,
                r.check.feasible() ? "feasible" : "INFEASIBLE", r.check.rate_hz);
  out = buf;
  if (!report.given.empty()) out += FormatGivenSummary(report);
  if (r.ramp_seconds > 0.0) {
    std::snprintf(buf, sizeof buf, "with %g s ramps from and to the home pose: %g s in trajectory.csv\n", r.ramp_seconds,
                  r.RobotTrajectory().duration());
    out += buf;
  }
  out += r.check.Explain();
  if (const std::string closest = r.check.ClosestObstacleLine(); !closest.empty()) out += closest + "\n";
  if (!r.check.feasible()) {
    out += "to relax:\n";
    for (const std::string& a : RelaxationAdvice(r.check, design, false)) out += "  " + a + "\n";
  }
  if (!r.usable()) out += "NOT USABLE: " + r.Rejection() + "\n";
  return out;
}

namespace {

// What design.json says of the settings, whatever the outcome.
nlohmann::json SettingsJson(const RobotModel& model, const DesignCommandOptions& options,
                            const std::vector<JointLimits>& used, const ActuatorLimits& actuators,
                            const std::vector<std::string>& parameter_names) {
  using nlohmann::json;
  const DesignOptions design = options.Resolved();
  auto limit = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json limits = json::array();
  for (const JointLimits& l : used) {
    limits.push_back({{"q_min", limit(l.q_min)}, {"q_max", limit(l.q_max)}, {"qd_max", limit(l.qd_max)},
                      {"qdd_max", limit(l.qdd_max)}, {"tau_max", limit(l.tau_max)}});
  }
  // The motors' limits with the transmission they act through (θ̇m = A·q̇, τm = A⁻ᵀ·τ).
  json motors = json::array();
  for (int k = 0; k < static_cast<int>(actuators.motors.size()); ++k) {
    const ActuatorLimit& l = actuators.motors[static_cast<size_t>(k)];
    const Eigen::VectorXd a = actuators.transmission.actuator_from_joint.row(k).transpose();
    motors.push_back({{"qd_max", limit(l.qd_max)}, {"tau_max", limit(l.tau_max)},
                      {"joints", actuators.DrivenJoints(model, k)},
                      {"actuator_from_joint", std::vector<double>(a.data(), a.data() + a.size())}});
  }
  return {
      {"command", options.command_line},
      {"robot", model.name()},
      {"model", std::string(kIdentificationModelNames.Name(options.model))},
      {"friction", options.model == IdentificationModel::kJointTorque ? json(options.friction) : json::array()},
      {"parameters", parameter_names},
      {"criterion", DesignCriterionName(design.criterion)},
      {"algorithm", DesignAlgorithmName(design.algorithm)},
      {"trajectory",
       {{"family", "fourier"},
        {"harmonics", design.harmonics},
        {"f0", design.f0},
        {"duration", design.period_duration()},
        {"rest_to_rest", design.rest_to_rest},
        {"ramp", design.ramp_seconds},
        {"samples", design.samples}}},
      {"search", {{"starts", design.starts}, {"seed", design.seed}, {"threads", design.threads},
                  {"max_evaluations", design.max_evaluations}, {"margin", design.margin},
                  {"clearance", design.clearance >= 0.0 ? json(design.clearance) : json(nullptr)}}},
      {"limits", limits},
      {"actuators", actuators.empty() ? json(nullptr) : json(motors)},
      {"transmission", options.transmission.empty() ? json(nullptr) : json(options.transmission)},
      {"scene", options.scene.empty() ? json(nullptr) : json(options.scene)},
      {"base_pose", design.base_pose.xyz_rpy},
  };
}

// The check's margins (a clearance margin names its pair).
nlohmann::json CheckJson(const FeasibilityCheck& check) {
  nlohmann::json margins = nlohmann::json::array();
  for (const ConstraintMargin& m : check.margins) {
    margins.push_back({{"joint", m.joint + 1}, {"quantity", m.quantity}, {"time", m.time}, {"value", m.value},
                       {"limit", m.limit}, {"margin", m.margin}});
    if (!m.pair.empty()) margins.back()["pair"] = m.pair;
    if (!m.obstacle.empty()) margins.back()["obstacle"] = m.obstacle;
    if (m.motor >= 0) {  // an actuator limit: the motor in place of the joint
      margins.back().erase("joint");
      margins.back()["motor"] = m.motor + 1;
      margins.back()["joints"] = m.driven;
    }
  }
  nlohmann::json out = {{"rate_hz", check.rate_hz}, {"feasible", check.feasible()}, {"margins", margins}};
  if (const ConstraintMargin* c = check.ClosestObstacle()) {
    out["closest_obstacle"] = {{"obstacle", c->obstacle}, {"link", c->link}, {"distance", c->value},
                               {"time", c->time}, {"minimum", c->limit}};
  }
  return out;
}

}  // namespace

namespace {

// design.json's "given": the motions, cond alone and with the new motion, σ
// predicted per base parameter (null where undetermined).
nlohmann::json GivenJson(const DesignCommandReport& report) {
  using nlohmann::json;
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json motions = json::array();
  for (const DesignCommandReport::GivenMotion& g : report.given) {
    motions.push_back({{"path", g.path}, {"kind", g.measured ? "log" : "designed trajectory"},
                       {"n_samples", g.n_samples}, {"duration", g.duration_s}, {"weight", g.weight}});
  }
  json sigma = json::array();
  for (Eigen::Index k = 0; k < report.sigma_given.size(); ++k) {
    sigma.push_back({{"parameter", report.parameter_names[static_cast<size_t>(k)]},
                     {"given_alone", number(report.sigma_given[k])},
                     {"with_new_motion", k < report.sigma_with_new.size() ? number(report.sigma_with_new[k]) : json(nullptr)}});
  }
  return {{"motions", motions},
          {"weighting", "a second of a given motion counts as a second of the new motion"},
          {"notes", report.given_notes},
          {"noise_sigma", number(std::sqrt(report.noise_variance))},
          {"given_alone", IdentifiabilityJson(report.given_alone)},
          {"with_new_motion", IdentifiabilityJson(report.result.final)},
          {"predicted_sigma", sigma}};
}

// design.json when no feasible design was found.
std::string FormatInfeasibleDesignJson(const RobotModel& model, const DesignCommandOptions& options,
                                       const DesignCommandReport& report) {
  const DesignInfeasibility& infeasible = report.result.infeasibility;
  nlohmann::json result = SettingsJson(model, options, report.limits, report.actuators, report.parameter_names);
  result["status"] = std::string(kDesignStatusNames.Name(report.status()));
  result["check"] = CheckJson(infeasible.check);
  result["infeasible"] = {{"before_search", infeasible.before_search},
                          {"explanation", infeasible.explanation},
                          {"advice", infeasible.advice}};
  return result.dump(2) + "\n";
}

}  // namespace

std::string FormatDesignJson(const RobotModel& model, const DesignCommandOptions& options,
                             const DesignCommandReport& report) {
  using nlohmann::json;
  // Without a motion: the settings and why. A motion that leaves parameters
  // unexcited has one: the full form, its status and why.
  if (report.status() != DesignStatus::kFeasible && report.status() != DesignStatus::kNotExcited)
    return FormatInfeasibleDesignJson(model, options, report);
  const DesignResult& r = report.result;
  json starts = json::array();
  for (const DesignStartSummary& s : r.starts) {
    starts.push_back({{"initial", s.initial_value},
                      {"best", std::isfinite(s.best_value) ? json(s.best_value) : json(nullptr)},
                      {"evaluations", s.evaluations},
                      {"feasible_at", s.feasible_at >= 0 ? json(s.feasible_at) : json(nullptr)},
                      {"status", s.status},
                      {"progressed", s.progressed},
                      {"outcome", s.outcome},
                      {"initial_violation", s.initial_violation},
                      {"final_violation", s.final_violation}});
  }
  json result = SettingsJson(model, options, report.limits, report.actuators, report.parameter_names);
  result["status"] = std::string(kDesignStatusNames.Name(report.status()));
  if (report.status() == DesignStatus::kNotExcited) result["not_excited"] = {{"explanation", r.infeasibility.explanation}};
  result.update({
      {"before", {{"criterion", r.initial_value}, {"identifiability", IdentifiabilityJson(r.initial)}}},
      {"after", {{"criterion", r.value}, {"identifiability", IdentifiabilityJson(r.final)}}},
      {"check", CheckJson(r.check)},
      {"csv", {{"rate_hz", options.csv_rate_hz}, {"columns", std::string(kTrajectoryCsvColumnsNames.Name(options.csv_columns))},
               {"duration", r.RobotTrajectory().duration()}}},
      {"starts", starts},
      {"home", {{"q", std::vector<double>(r.home.data(), r.home.data() + r.home.size())}, {"source", r.home_source}}},
      {"evaluations", r.evaluations},
      {"wall_seconds", r.wall_seconds},
      {"stopped", r.stopped},
      {"verdict", {{"usable", r.usable()}, {"reason", r.Rejection()}}},
      {"clearance_pairs", {{"excluded", report.clearance_excluded}, {"held_at_home", report.clearance_held}}},
  });
  if (!report.given.empty()) result["given"] = GivenJson(report);
  return result.dump(2) + "\n";
}

}  // namespace idbench
