// A recorded joint log handed out in chunks of samples, in time order (style.md
// "Logs are streams"). CSV files, multi-file descriptions, one-value-per-line
// files, rosbag2 bags (.db3 / .mcap) and in-memory arrays are implementations;
// the preparation pipeline (window, resample, filter, regressor, fold) consumes
// chunks, so memory never grows with the log's length.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "idbench/engine/measurements.h"
#include "idbench/engine/transmission.h"

namespace idbench {

// What a source holds, known when it is opened (before the first chunk).
struct JointLogLayout {
  std::string source;  // the file or directory, for messages
  int n_dof = 0;
  bool has_qd = false, has_qdd = false, has_tau = false;  // recorded columns (tau: or currents, see below)
  bool torque_from_currents = false;  // tau = K·i (drive gains applied by the source)
  bool tau_is_current = false;        // TorqueColumns::kCurrents: tau holds the currents [A]
  std::optional<double> rate_hz;      // set when t comes from a rate (no time column)
  std::string record_name = "line";   // what JointLogChunk::records counts: "line", "row", "message", "sample"
  std::vector<double> time_window;    // {T0, T1} [s] a log description asks for (the reader keeps T0 <= t <= T1)
  // Set when actuator-side columns were read through it: the samples are
  // joint-side already; what the actuator-side model terms need (A).
  std::optional<Transmission> transmission;
  std::vector<std::string> notes;     // how columns/joints were mapped, for stdout
  std::vector<std::string> warnings;  // for stderr
};

// Up to max_samples consecutive samples. samples.qd/qdd/tau are 0 × 0 when
// not recorded (as in JointLog).
struct JointLogChunk {
  JointLog samples;                   // angles in rad, tau in N m (or A when tau_is_current)
  std::vector<std::int64_t> records;  // per sample, where it came from (file line, message index), for messages
};

class JointLogSource {
 public:
  virtual ~JointLogSource() = default;
  virtual const JointLogLayout& layout() const = 0;
  // The next up-to-max_samples samples (max_samples >= 1) into *chunk,
  // replacing its contents. Returns false, with an empty chunk, at the end.
  // Throws std::invalid_argument naming source:record for bad data (a field
  // that is not a number, time not increasing across chunks too, a position
  // outside the joint limits, ...), as the whole-file readers do.
  virtual bool Next(Eigen::Index max_samples, JointLogChunk* chunk) = 0;
  // Back to the first sample, for a second pass.
  virtual void Rewind() = 0;
};

}  // namespace idbench
