// The seed paper's per-body identifier: mass and principal inertias of every
// body from its hinge wrenches and its motion, by rank-revealing least squares
// over the chosen samples (eqs. 24–27).
#pragma once

#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/measurements.h"
#include "idbench/ident/least_squares.h"

namespace idbench {

// Parameter names per body, in report order: the mass from the Newton rows of
// world axis e1, e2, e3 alone (paper Table 2), the mass from all three, and
// the principal moments about the centroid (Table 3).
inline const std::vector<std::string>& PerBodyParameterNames() {
  static const std::vector<std::string> names{"m_e1", "m_e2", "m_e3", "m", "J11", "J22", "J33"};
  return names;
}

struct ParameterResult {
  std::string name;
  double true_value = 0.0;    // from the model that generated the data
  double identified = 0.0;    // NaN when not identifiable
  bool identifiable = false;
  std::string reason;         // why not identifiable ("" if it is)
  double abs_error = 0.0;     // identified − true (NaN when not identifiable)
  double rel_error = 0.0;     // |abs_error| / |true| (NaN when not identifiable)
};

struct BlockReport {
  int rank = 0;
  int n_unknowns = 0;
  double cond = 0.0;           // cond of the identifiable columns
  double residual_norm = 0.0;  // ‖K x − L‖
};

struct BodyResult {
  std::string name;
  std::vector<ParameterResult> parameters;  // PerBodyParameterNames() order
  BlockReport newton;                       // combined-mass block (3 rows per sample)
  BlockReport euler;                        // inertia block (3 rows per sample)
};

struct PerBodyIdentificationResult {
  std::vector<BodyResult> bodies;
  int n_samples = 0;
  double max_rel_error = 0.0;  // over identifiable parameters
  std::string max_rel_error_at;  // "B2.J22"
};

// Identifies every body from the log steps `steps` (indices into log.steps).
// The model supplies the geometry (hinge points, centroid) and the true values
// the errors are measured against. Throws std::invalid_argument if steps is
// empty or an index is out of range.
PerBodyIdentificationResult IdentifyPerBody(const RobotModel& model, const SimulationLog& log,
                                            const std::vector<int>& steps,
                                            const LeastSquaresOptions& options = {});

}  // namespace idbench
