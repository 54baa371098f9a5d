// Bringing a joint log recorded with irregular time stamps (controller jitter,
// a dropped sample) onto a uniform grid, so the zero-phase filter and the
// central differences of signal_filter.h, which need uniform sampling, apply.
//
// Grid: the median step h (the controller's nominal period: jitter and the odd
// dropped sample move the mean, not the median), t_k = t_0 + k h,
// k = 0..⌊(t_end − t_0)/h⌋. Interpolation:
//   - q (and qd when recorded): piecewise cubic Hermite, with the recorded
//     derivative (qd for q, qdd for qd) as the slope where the log has it,
//     error ≤ h⁴/384 · max|x⁗| on a step of length h; else with the slope of
//     the parabola through the sample and its two neighbours (three-point,
//     O(h²) slopes), error ≤ h⁴/384 · max|x⁗| + (4/27) h (|δ_k| + |δ_k+1|),
//     |δ| ≤ h_a h_b/6 · max|x‴| for the neighbouring steps h_a, h_b (h_a(h_a + h_b)/6 at the ends).
//     Positions and velocities are smooth, so a cubic through values and
//     slopes is accurate to far below encoder resolution at control rates.
//   - qdd, tau (and motor currents): linear, error ≤ h²/8 · max|x″|. These are
//     noisy and may step (Coulomb friction): linear interpolation is a convex
//     combination of the two neighbours, so it neither overshoots nor amplifies
//     noise.
// A step longer than the gap bound is not interpolated: it is reported
// (status kGap) for the caller to name the line.
#pragma once

#include <string>

#include <Eigen/Core>

#include "idbench/engine/measurements.h"

namespace idbench {

struct ResamplingOptions {
  // Steps within this fraction of the median step count as uniform: the log
  // passes through untouched (so logs written at a fixed rate keep their values).
  double uniform_tolerance = 1e-6;
  // A step longer than this is a gap [s]; 0: kDefaultGapSteps × the median step.
  double max_gap_s = 0.0;

  static constexpr double kDefaultGapSteps = 10.0;
  static constexpr double kMaxUniformTolerance = 0.1;

  bool IsValid(std::string* why) const;
};

enum class ResamplingStatus {
  kUniform,    // steps within uniform_tolerance of the median: *out = the log
  kResampled,  // *out holds the log on the uniform grid
  kGap,        // a step longer than the gap bound: nothing resampled
};

struct ResamplingSummary {
  ResamplingStatus status = ResamplingStatus::kUniform;
  int n_samples_in = 0;
  int n_samples_out = 0;
  double min_step_s = 0.0;    // shortest step of the log [s]
  double max_step_s = 0.0;    // longest step [s]
  double grid_step_s = 0.0;   // the median step: the grid's step [s]
  double gap_bound_s = 0.0;   // steps longer than this are gaps [s]
  int gap_sample = -1;        // kGap: index of the first sample after a gap
  std::string method;         // which interpolation each signal got
  // One line for the user: what was done, with the grid (or where the gap is).
  std::string BriefReport() const;
};

// Piecewise cubic Hermite interpolation of each column of x (samples in rows)
// at t_out. `slope` holds dx/dt at the samples (same shape as x) or is empty:
// then three-point slopes (see the file comment). t strictly increasing with
// at least 2 samples (3 without slopes); t_out non-decreasing within
// [t_0, t_end]. Throws std::invalid_argument otherwise.
Eigen::MatrixXd InterpolateCubicHermite(const Eigen::VectorXd& t, const Eigen::MatrixXd& x,
                                        const Eigen::MatrixXd& slope, const Eigen::VectorXd& t_out);

// Linear interpolation of each column; the same requirements (2 samples).
Eigen::MatrixXd InterpolateLinear(const Eigen::VectorXd& t, const Eigen::MatrixXd& x, const Eigen::VectorXd& t_out);

// Median of the steps t[i] − t[i−1] [s]. Throws std::invalid_argument for
// fewer than 2 samples.
double MedianStep(const Eigen::VectorXd& t);

// Brings `log` (t strictly increasing, at least 3 samples; q; qd, qdd and tau
// each present or empty) onto the uniform grid of the median step, as the file
// comment says, into *out. Returns the summary; on kGap *out is left as it was.
// Throws std::invalid_argument for invalid options, a log with fewer than 3
// samples, time not strictly increasing, or signals whose rows differ from t.
ResamplingSummary ResampleJointLog(const JointLog& log, const ResamplingOptions& options, JointLog* out);

}  // namespace idbench
