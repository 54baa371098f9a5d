#include "idbench/logs/log_resampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

std::string Num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", value);
  return buffer;
}

// Checks t (strictly increasing, at least min_samples) and t_out (non-decreasing,
// inside [t_0, t_end]) and that x has one row per sample.
void CheckInterpolation(const Eigen::VectorXd& t, const Eigen::MatrixXd& x, const Eigen::VectorXd& t_out,
                        Eigen::Index min_samples, const char* what) {
  const std::string name(what);
  if (t.size() < min_samples) {
    throw std::invalid_argument(name + ": expected at least " + std::to_string(min_samples) + " samples, got " +
                                std::to_string(t.size()));
  }
  if (x.rows() != t.size()) {
    throw std::invalid_argument(name + ": expected " + std::to_string(t.size()) + " rows (t.size()), got " +
                                std::to_string(x.rows()));
  }
  for (Eigen::Index i = 1; i < t.size(); ++i) {
    if (!(t[i] > t[i - 1])) {
      throw std::invalid_argument(name + ": expected strictly increasing t, got t[" + std::to_string(i) +
                                  "] = " + Num(t[i]) + " after " + Num(t[i - 1]));
    }
  }
  for (Eigen::Index k = 0; k < t_out.size(); ++k) {
    if (!(t_out[k] >= t[0] && t_out[k] <= t[t.size() - 1]) || (k > 0 && t_out[k] < t_out[k - 1])) {
      throw std::invalid_argument(name + ": expected non-decreasing output times in [" + Num(t[0]) + ", " +
                                  Num(t[t.size() - 1]) + "], got " + Num(t_out[k]) + " at " + std::to_string(k));
    }
  }
}

// Slopes of the parabola through each sample and its two neighbours (the
// one-sided parabola through the first or last three at the ends), on
// non-uniform steps: O(h_a h_b) accurate.
Eigen::MatrixXd ThreePointSlopes(const Eigen::VectorXd& t, const Eigen::MatrixXd& x) {
  const Eigen::Index n = t.size();
  Eigen::MatrixXd d(n, x.cols());
  for (Eigen::Index i = 1; i + 1 < n; ++i) {
    const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
    d.row(i) = (h1 / (h0 + h1)) * (x.row(i) - x.row(i - 1)) / h0 + (h0 / (h0 + h1)) * (x.row(i + 1) - x.row(i)) / h1;
  }
  // Ends: derivative at t_0 of the parabola through samples 0, 1, 2 (mirrored at the end).
  auto end_slope = [&](Eigen::Index a, Eigen::Index b, Eigen::Index c) -> Eigen::RowVectorXd {
    const double h0 = t[b] - t[a], h1 = t[c] - t[b];  // signed: negative at the far end
    return -(2.0 * h0 + h1) / (h0 * (h0 + h1)) * x.row(a) + (h0 + h1) / (h0 * h1) * x.row(b) -
           h0 / (h1 * (h0 + h1)) * x.row(c);
  };
  d.row(0) = end_slope(0, 1, 2);
  d.row(n - 1) = end_slope(n - 1, n - 2, n - 3);
  return d;
}

}  // namespace

bool ResamplingOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  if (!(uniform_tolerance >= 0.0 && uniform_tolerance <= kMaxUniformTolerance)) {
    return fail("expected a uniform tolerance in [0, " + Num(kMaxUniformTolerance) + "], got " +
                Num(uniform_tolerance));
  }
  if (!(max_gap_s >= 0.0) || !std::isfinite(max_gap_s)) {
    return fail("expected a gap bound >= 0 s (0: " + Num(kDefaultGapSteps) + " median steps), got " + Num(max_gap_s));
  }
  return true;
}

std::string ResamplingSummary::BriefReport() const {
  const std::string steps = Num(1e3 * min_step_s) + "–" + Num(1e3 * max_step_s) + " ms";
  switch (status) {
    case ResamplingStatus::kUniform:
      return "uniform sampling: " + std::to_string(n_samples_in) + " samples, step " + Num(1e3 * grid_step_s) + " ms";
    case ResamplingStatus::kResampled:
      return "resampled " + std::to_string(n_samples_in) + " samples with steps " + steps + " onto a uniform " +
             Num(1e3 * grid_step_s) + " ms grid (the median step) of " + std::to_string(n_samples_out) +
             " samples (" + method + ")";
    case ResamplingStatus::kGap:
      return "a gap of " + Num(1e3 * max_step_s) + " ms before sample " + std::to_string(gap_sample) +
             ", longer than the bound " + Num(1e3 * gap_bound_s) + " ms (median step " + Num(1e3 * grid_step_s) +
             " ms)";
  }
  return "";
}

Eigen::MatrixXd InterpolateCubicHermite(const Eigen::VectorXd& t, const Eigen::MatrixXd& x,
                                        const Eigen::MatrixXd& slope, const Eigen::VectorXd& t_out) {
  CheckInterpolation(t, x, t_out, slope.size() > 0 ? 2 : 3, "cubic Hermite interpolation");
  if (slope.size() > 0 && (slope.rows() != x.rows() || slope.cols() != x.cols())) {
    throw std::invalid_argument("cubic Hermite interpolation: expected slopes of " + std::to_string(x.rows()) + "x" +
                                std::to_string(x.cols()) + ", got " + std::to_string(slope.rows()) + "x" +
                                std::to_string(slope.cols()));
  }
  const Eigen::MatrixXd d = slope.size() > 0 ? slope : ThreePointSlopes(t, x);
  Eigen::MatrixXd y(t_out.size(), x.cols());
  Eigen::Index k = 0;  // interval [t_k, t_k+1] of the current output time
  for (Eigen::Index o = 0; o < t_out.size(); ++o) {
    while (k + 2 < t.size() && t_out[o] > t[k + 1]) ++k;
    const double h = t[k + 1] - t[k];
    const double s = (t_out[o] - t[k]) / h;
    // Hermite basis on [0, 1]: values at 0 and 1, slopes (scaled by h) at 0 and 1.
    const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s), h10 = s * (1.0 - s) * (1.0 - s);
    const double h01 = s * s * (3.0 - 2.0 * s), h11 = s * s * (s - 1.0);
    y.row(o) = h00 * x.row(k) + h01 * x.row(k + 1) + h * (h10 * d.row(k) + h11 * d.row(k + 1));
  }
  return y;
}

Eigen::MatrixXd InterpolateLinear(const Eigen::VectorXd& t, const Eigen::MatrixXd& x, const Eigen::VectorXd& t_out) {
  CheckInterpolation(t, x, t_out, 2, "linear interpolation");
  Eigen::MatrixXd y(t_out.size(), x.cols());
  Eigen::Index k = 0;
  for (Eigen::Index o = 0; o < t_out.size(); ++o) {
    while (k + 2 < t.size() && t_out[o] > t[k + 1]) ++k;
    const double s = (t_out[o] - t[k]) / (t[k + 1] - t[k]);
    y.row(o) = (1.0 - s) * x.row(k) + s * x.row(k + 1);
  }
  return y;
}

double MedianStep(const Eigen::VectorXd& t) {
  if (t.size() < 2) throw std::invalid_argument("median step: expected at least 2 samples, got " + std::to_string(t.size()));
  std::vector<double> steps(static_cast<size_t>(t.size() - 1));
  for (Eigen::Index i = 1; i < t.size(); ++i) steps[static_cast<size_t>(i - 1)] = t[i] - t[i - 1];
  const size_t mid = steps.size() / 2;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(mid), steps.end());
  const double upper = steps[mid];
  if (steps.size() % 2 == 1) return upper;
  const double lower = *std::max_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

ResamplingSummary ResampleJointLog(const JointLog& log, const ResamplingOptions& options, JointLog* out) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("resampling options: " + why);
  const Eigen::VectorXd& t = log.t;
  const Eigen::Index n = t.size();
  if (n < 3) throw std::invalid_argument("resampling: expected at least 3 samples, got " + std::to_string(n));
  for (const Eigen::MatrixXd* x : {&log.q, &log.qd, &log.qdd, &log.tau}) {
    if (x->size() > 0 && x->rows() != n) {
      throw std::invalid_argument("resampling: expected signals of " + std::to_string(n) + " rows (t.size()), got " +
                                  std::to_string(x->rows()));
    }
  }

  // Steps: increasing, their spread, and the gaps.
  ResamplingSummary summary;
  summary.n_samples_in = static_cast<int>(n);
  summary.grid_step_s = MedianStep(t);
  summary.min_step_s = summary.max_step_s = t[1] - t[0];
  summary.gap_bound_s = options.max_gap_s > 0.0 ? options.max_gap_s : ResamplingOptions::kDefaultGapSteps * summary.grid_step_s;
  for (Eigen::Index i = 1; i < n; ++i) {
    const double step = t[i] - t[i - 1];
    if (!(step > 0.0)) {
      throw std::invalid_argument("resampling: expected strictly increasing t, got t[" + std::to_string(i) + "] = " +
                                  Num(t[i]) + " after " + Num(t[i - 1]));
    }
    summary.min_step_s = std::min(summary.min_step_s, step);
    summary.max_step_s = std::max(summary.max_step_s, step);
    if (step > summary.gap_bound_s && summary.gap_sample < 0) summary.gap_sample = static_cast<int>(i);
  }
  const double h = summary.grid_step_s;
  const double spread = std::max(summary.max_step_s - h, h - summary.min_step_s);
  if (spread <= options.uniform_tolerance * h) {
    summary.status = ResamplingStatus::kUniform;
    summary.n_samples_out = summary.n_samples_in;
    *out = log;
    return summary;
  }
  if (summary.gap_sample >= 0) {
    summary.status = ResamplingStatus::kGap;
    summary.max_step_s = t[summary.gap_sample] - t[summary.gap_sample - 1];
    return summary;
  }

  // The grid t_0 + k h up to the last sample (a partial last step is dropped).
  const Eigen::Index n_out = static_cast<Eigen::Index>(std::floor((t[n - 1] - t[0]) / h * (1.0 + 1e-12))) + 1;
  Eigen::VectorXd grid(n_out);
  for (Eigen::Index k = 0; k < n_out; ++k) grid[k] = std::min(t[0] + static_cast<double>(k) * h, t[n - 1]);

  // Positions and velocities: cubic Hermite with the recorded derivative where
  // there is one; accelerations and torques: linear.
  const bool has_qd = log.qd.size() > 0, has_qdd = log.qdd.size() > 0, has_tau = log.tau.size() > 0;
  JointLog resampled;
  resampled.t = grid;
  resampled.q = InterpolateCubicHermite(t, log.q, has_qd ? log.qd : Eigen::MatrixXd(), grid);
  summary.method = std::string("cubic Hermite on q ") + (has_qd ? "with the recorded qd" : "with three-point slopes");
  if (has_qd) {
    resampled.qd = InterpolateCubicHermite(t, log.qd, has_qdd ? log.qdd : Eigen::MatrixXd(), grid);
    summary.method += std::string(", on qd ") + (has_qdd ? "with the recorded qdd" : "with three-point slopes");
  }
  std::string linear;
  if (has_qdd) {
    resampled.qdd = InterpolateLinear(t, log.qdd, grid);
    linear = "qdd";
  }
  if (has_tau) {
    resampled.tau = InterpolateLinear(t, log.tau, grid);
    linear += linear.empty() ? "tau" : ", tau";
  }
  if (!linear.empty()) summary.method += "; linear on " + linear;
  summary.status = ResamplingStatus::kResampled;
  summary.n_samples_out = static_cast<int>(n_out);
  *out = std::move(resampled);
  return summary;
}

}  // namespace idbench
