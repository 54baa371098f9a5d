// What the GUI works on, without any drawing: the robot, the limit table, the
// option structs of the command line (design, simulate, identify, compare)
// that the panels edit, the background jobs that run the command library on
// them, and their results. Every action reports failure as a message in the
// session and leaves the rest as it was (nothing the user made is lost).
//
// Thread use: everything here belongs to the UI thread. Jobs compute on
// their own threads from copies of the options and hand their results back
// through Poll(); only the design's progress curve is shared (locked).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "idbench/workbench/commands/compare_command.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/commands/payload_command.h"
#include "idbench/workbench/commands/run_command.h"
#include "idbench/engine/measurements.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/engine/transmission.h"
#include "idbench/gui/background_job.h"
#include "idbench/workbench/commands/simulate_command.h"

namespace idbench::gui {

struct SessionOptions {
  std::string robot = "paper6r";   // built-in name or URDF path
  std::string out_dir = "out/gui"; // where simulate, compare and export write
};

struct SessionMessage {
  enum class Level { kInfo, kError };
  Level level = Level::kInfo;
  std::string text;
};

enum class JobKind { kDesign, kSimulate, kIdentify, kPerBody, kCompare, kReport, kPayload };
inline constexpr int kJobKinds = 7;
// "design", "simulate", "identify", "per-body", "compare", "report", "payload" (script names).
const char* JobName(JobKind kind);
std::optional<JobKind> ParseJobName(const std::string& name);

// One row of the identification table: a base parameter.
struct IdentifiedRow {
  std::string name;           // the combination of standard parameters it stands for
  double model_value = 0.0;   // the robot file's value (the truth for a simulated log)
  double identified = 0.0;    // the chosen estimator's; NaN when the log does not determine it
  double relative_error = 0.0;     // (identified − model) / |model|; NaN when model is 0
  double sigma_percent = 0.0;      // 100 σ/|β̂| of the linear fit
  ParameterStatus status = ParameterStatus::kDetermined;  // from β̂ and σ (linear_estimator.h)
};

// One row of the payload table: a quantity of PayloadQuantityNames.
struct PayloadRow {
  std::string name;            // "mass", "com_x", ..., "Izz"
  std::string unit;            // "kg", "m", "kg m2"
  double value = 0.0;          // the estimate; NaN when not identifiable
  double sigma = 0.0;          // its σ; NaN when not identifiable
  std::string value_text;      // as shown: the number, or "not identifiable"
  std::string sigma_text;      // as shown: the number, or "-"
  std::string status;          // "determined", "poorly determined" (σ above the verdict's bound), "not identifiable"
  std::string reason;          // why not identifiable ("" when it is)
};

class Session {
 public:
  explicit Session(const SessionOptions& options);
  ~Session();  // stops running jobs and waits for them
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // ---- Robot -------------------------------------------------------------
  const RobotModel& model() const { return *model_; }
  const std::string& robot_source() const { return robot_source_; }
  // The robot URDF's ros_control transmission (design.transmission "urdf");
  // nullopt when it has none (a built-in robot).
  const std::optional<Transmission>& robot_transmission() const { return robot_transmission_; }
  // Loads a built-in robot or a URDF. On failure (unknown name, unreadable or
  // unsupported file) keeps the current robot and posts the error; refused
  // while a job runs. Resets the limit table and the results.
  bool LoadRobot(const std::string& name_or_path);

  // The design's limits, one per joint: the robot file's, as the user edits them.
  std::vector<JointLimits> limits;
  // What FillMissingLimits puts where the table has no finite limit.
  JointLimits fill_limits{.q_min = -3.0, .q_max = 3.0, .qd_max = 1.0, .qdd_max = 3.0};
  void FillMissingLimits();
  void ResetLimits();  // back to the robot file's

  // ---- Options the panels edit (the command line's structs) ---------------
  DesignCommandOptions design;
  SimulateOptions simulate;
  IdentifyOptions identify;
  CompareOptions compare;
  RunOptions per_body;  // the per-body experiment (`idbench run`): Bullet's hinge wrenches, no noise
  PayloadOptions payload;  // the Payload tab (`idbench payload`): its own robot (identified URDF), out_dir its export folder
  std::string out_dir;
  // The motion shown, simulated and exported: "designed" or a built-in motion name.
  std::string motion = "paper";
  double builtin_duration = 10.0;  // [s] of built-in motions
  // Motions of the compare panel besides the designed one (built-in names).
  std::vector<std::string> compare_builtins{"paper"};

  // ---- Jobs ---------------------------------------------------------------
  void StartDesign();
  void StopDesign();
  void StartSimulate();
  void StartIdentify();
  // Asks a running identify to stop: it ends with "cancelled", the previous
  // identification kept.
  void CancelIdentify();
  void StartCompare();
  // The per-body experiment along the current motion (its whole duration).
  void StartPerBody();
  // The identification's report (`identify --report`) into out_dir.
  void StartReport();
  // RunPayload on `payload` (its robot loaded on the worker); the previous
  // estimate is kept when it fails.
  void StartPayload();
  bool running(JobKind kind) const { return jobs_[static_cast<int>(kind)].running(); }
  bool any_running() const;
  // On the UI thread, every frame: applies the results of finished jobs.
  void Poll();
  // Blocks until every running job has finished, then Poll (tests, shutdown).
  void WaitForJobs();

  // ---- Results ------------------------------------------------------------
  const std::optional<DesignCommandReport>& design_report() const { return design_report_; }
  // Best feasible criterion over all starts after each progress report (live).
  std::vector<double> DesignCurve() const;
  // How far the running identify is (live): RunIdentify's stages, then the
  // predicted torques of the plots.
  IdentifyProgress identify_progress() const;
  const std::optional<JointLog>& log() const { return log_; }
  const std::optional<IdentifyReport>& identify_report() const { return identify_report_; }
  // The options identify_report() was made with.
  const IdentifyOptions& identified_with() const { return identified_with_; }
  // Measured and predicted torque of the identification (PredictIdentifiedTorques)
  // on its log and on the held-out one (when identified with one).
  const std::optional<TorqueSeries>& fit_torques() const { return fit_torques_; }
  const std::optional<TorqueSeries>& held_out_torques() const { return held_out_torques_; }
  std::vector<IdentifiedRow> IdentifiedRows() const;
  // Standard parameters no motion can excite (no effect on any torque).
  std::vector<std::string> UnexcitedParameters() const;
  const std::optional<CompareReport>& compare_report() const { return compare_report_; }
  const std::optional<PerBodyIdentificationResult>& per_body_result() const { return per_body_result_; }
  const std::optional<PayloadSummary>& payload_summary() const { return payload_summary_; }
  const PayloadOptions& payload_estimated_with() const { return payload_estimated_with_; }  // of payload_summary()
  // The payload's 10 quantities as the Payload tab shows them (none before an estimate).
  std::vector<PayloadRow> PayloadRows() const;

  // The motion selected by `motion` (the designed one once it exists); null
  // when "designed" is selected before any design finished.
  const Trajectory* current_motion() const;
  // Bumped whenever current_motion() may have changed (robot, motion, design).
  int motion_version() const { return motion_version_; }
  void SelectMotion(const std::string& name);

  // ---- Export (into out_dir) ----------------------------------------------
  bool ExportTrajectoryJson();   // the designed motion's coefficients
  bool ExportTrajectoryCsv();    // the current motion at the design's csv rate
  // The identification's files as `idbench identify` writes them:
  // identified.json always; identified.urdf, identified.xml (MJCF) and
  // joints.yaml when the verdict is fit to load (else an error says why).
  bool ExportIdentifiedModel();
  // The payload's files as `idbench payload` writes them (PayloadFiles), into
  // payload.out_dir: payload.json always, payload.urdf.xml when the verdict
  // allows it (else an error says why).
  bool ExportPayload();
  std::string OutPath(const std::string& file) const;

  // ---- Messages -----------------------------------------------------------
  const std::vector<SessionMessage>& messages() const { return messages_; }
  void Info(const std::string& text);
  void Error(const std::string& text);
  // The last error posted, or "".
  std::string last_error() const;

 private:
  BackgroundJob& job(JobKind kind) { return jobs_[static_cast<int>(kind)]; }
  bool StartJob(JobKind kind, BackgroundJob::Work work);
  // Applies the results of finished jobs (waiting for running ones if asked).
  void CollectJobs(bool wait);
  void RebuildBuiltinMotion();
  // Writes the designed motion's JSON into out_dir; returns its path.
  std::string WriteDesignedTrajectory();
  // Writes content() to out_dir/file atomically; a failure becomes a message.
  bool Export(const std::string& file, const std::function<std::string()>& content);

  std::shared_ptr<const RobotModel> model_;
  std::string robot_source_;
  std::optional<Transmission> robot_transmission_;
  std::unique_ptr<Trajectory> builtin_motion_;
  std::string builtin_motion_key_;
  int motion_version_ = 0;

  std::optional<DesignCommandReport> design_report_;
  bool DesignedMotionExportable();  // Error() says why not
  std::optional<JointLog> log_;
  std::optional<IdentifyReport> identify_report_;
  IdentifyOptions identified_with_;   // the options of identify_report_
  std::shared_ptr<const RobotModel> identified_model_;  // the robot mounted at identified_with_.base_pose
  std::string simulated_log_;         // the log Simulate last wrote: its report may speak of a truth
  std::optional<TorqueSeries> fit_torques_, held_out_torques_;
  std::optional<CompareReport> compare_report_;
  std::optional<PerBodyIdentificationResult> per_body_result_;
  std::optional<PayloadSummary> payload_summary_;
  PayloadOptions payload_estimated_with_;              // the options of payload_summary_
  std::shared_ptr<const RobotModel> payload_model_;    // the robot payload_summary_ was estimated on

  mutable std::mutex curve_mutex_;
  std::vector<double> curve_;             // best over all starts, per progress report
  std::vector<double> start_best_;        // per start (worker side)

  mutable std::mutex identify_progress_mutex_;
  IdentifyProgress identify_progress_;    // worker side writes, the UI reads

  std::vector<SessionMessage> messages_;
  BackgroundJob jobs_[kJobKinds];
};

}  // namespace idbench::gui
