// Identifies the built-in PUMA 560 from a noise-free simulated log (Bullet,
// exact qd, qdd) through the installed libraries, and checks the identified
// base parameters against the robot file's own (β_model = C·π_model), the
// log passed through the joint-log CSV (idbench::logs) as a file would be.
// Prints the numbers; exits 1 when they disagree.
#include <cmath>
#include <cstdio>

#include "idbench/engine/robot_library.h"
#include "idbench/ident/joint_torque_identifier.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "idbench/workbench/version.h"

int main() {
  using namespace idbench;
  const RobotModel model = LoadRobot("puma560").model;
  SimulateOptions simulate;
  simulate.trajectory = "general";
  simulate.duration = 4.0;
  simulate.sensors.rate_hz = 200.0;
  const JointLog log = ParseJointLogCsv(FormatJointLogCsv(SimulateJointLog(model, simulate)), model, "log.csv");

  JointTorqueOptions options;
  options.friction = {.viscous = true, .coulomb = true, .rotor_inertia = true};
  const JointTorqueIdentification id = IdentifyJointTorque(model, log, options);
  // Relative to the largest parameter: the dynamic range of β spans decades.
  const double error = (id.beta - id.beta_model).cwiseAbs().maxCoeff() / id.beta_model.cwiseAbs().maxCoeff();
  std::printf("idbench %s (git %s): %d samples, %d base parameters, cond %.4g, fit error %.3g, "
              "max |beta - beta_model| / max |beta_model| = %.3g\n",
              Version(), GitRevision(), log.n_samples(), id.base.n_base(), id.linear.cond, id.fit.relative_error,
              error);
  return std::isfinite(error) && error < 1e-6 && id.fit.relative_error < 1e-6 ? 0 : 1;
}
