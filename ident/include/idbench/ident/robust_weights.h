// Weights of single equation rows for iteratively reweighted least squares
// (IRLS, an M-estimator: Huber 1964; Holland & Welsch 1977): each row
// τ_i ≈ W_i β of joint j gets, from its residual r_i = τ_i − W_i β at a
// fixed β and the joint's robust scale s_j,
//   w_i = ψ(u)/u / s_j²,   u = r_i / s_j,
// Huber:         ψ(u)/u = min(1, c/|u|)            (c = 1.345: 95 % efficient on Gaussian noise)
// Tukey bisquare: ψ(u)/u = (1 − (u/c)²)² for |u| < c, else 0   (c = 4.685, the same efficiency),
// so that Σ_i w_i (τ_i − W_i β)² is the M-estimator's cost linearised at β:
// the rows of a joint weighted by 1/s_j² as in WLS, gross outliers down to
// a weight ∝ 1/|r| (Huber) or 0 (Tukey).
//
// The scale is s_j = MAD_j / 0.6745 with MAD_j = median |r| over joint j's
// rows (the median about 0: residuals of a fit with an offset or a
// constant column are centred). The median of a log that is streamed, not
// held, comes from a histogram of |r| (IrlsPassRecord): kHistogramBins
// log-spaced bins over [10⁻¹², 10⁴] × the joint's RMS residual, the median
// interpolated in its bin (bins 0.22 % wide).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string_view>
#include <vector>

#include "idbench/engine/enum_names.h"

namespace idbench {

enum class RobustLoss { kHuber, kTukey };
inline constexpr EnumNames<RobustLoss, 2> kRobustLossNames{"robust_loss", {"huber", "tukey"}};
// The tuning constant of 95 % efficiency on Gaussian noise: 1.345 (Huber), 4.685 (Tukey).
double DefaultTuning(RobustLoss loss);

// The weights of one IRLS pass: fixed β (where the residuals are taken) and
// per-joint scales.
struct RobustRowWeights {
  RobustLoss loss = RobustLoss::kHuber;
  double tuning = 1.345;   // c
  Eigen::VectorXd beta;    // β the residuals are taken at (p)
  Eigen::VectorXd scale;   // s_j [N m] (n_dof), > 0

  // w_i of a row of joint j with residual r (above). Joint j must be in range.
  double Weight(int joint, double residual) const {
    const double s = scale[joint];
    const double u = std::abs(residual) / (tuning * s);
    double psi_over_u = 1.0;  // of u/c
    if (loss == RobustLoss::kHuber) {
      psi_over_u = u <= 1.0 ? 1.0 : 1.0 / u;
    } else {
      psi_over_u = u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
    return psi_over_u / (s * s);
  }
  // ψ'(u) / s_j² of that row: its weight in the M-estimator's Hessian
  // Σ_i ψ'(u_i)/s_j² W_iᵀW_i, the bread of its sandwich (Huber 1981, §7.6).
  double Slope(int joint, double residual) const {
    const double s = scale[joint];
    const double u = std::abs(residual) / (tuning * s);
    double slope = 0.0;
    if (loss == RobustLoss::kHuber) slope = u <= 1.0 ? 1.0 : 0.0;
    else if (u < 1.0) slope = (1.0 - u * u) * (1.0 - 5.0 * u * u);
    return slope / (s * s);
  }
};

// What an IRLS pass records of its rows, in memory independent of their
// number (n_dof × (kHistogramBins + 2 p²)): per joint, the median of |r|
// from a log-spaced histogram (above), and the sums Σ ψ'/s² x xᵀ (the
// Hessian) and Σ (w r)² x xᵀ (the scores' white Ω) of its rows x.
class IrlsPassRecord {
 public:
  static constexpr int kHistogramBins = 16384;
  // reference: per joint, the RMS residual the bins are placed around (> 0;
  // a smaller value is raised to 10⁻³⁰⁰); p parameters. Without sums, only
  // the histogram is kept (Hessian() and WhiteScoreCovariance() are zero):
  // what a pass needs for its scale, the sums wanted of the last pass only.
  IrlsPassRecord(const Eigen::VectorXd& reference, int n_parameters, bool sums = true);

  // Adds rows of `joint`: their residuals r (m), and x their regressor rows
  // restricted to `columns` (m × columns.size(); indices into β, as a
  // JointRowFactor's, the same at every call for one joint) under `weights`,
  // as one matrix product per call. Rows of different joints may be added
  // from different threads, rows of one joint from one at a time.
  void AddRows(int joint, const Eigen::Ref<const Eigen::VectorXd>& residuals, const Eigen::Ref<const Eigen::MatrixXd>& x,
               const std::vector<int>& columns, const RobustRowWeights& weights);
  // Only the residual (the histogram).
  void Add(int joint, double residual);
  // Σ over joints and rows of ψ'/s² x xᵀ, and of (w r)² x xᵀ (p × p).
  Eigen::MatrixXd Hessian() const;
  Eigen::MatrixXd WhiteScoreCovariance() const;
  // Median |r| of each joint's rows (n_dof); 0 for a joint without rows.
  Eigen::VectorXd Median() const;
  // Rows added per joint.
  Eigen::Index count(int joint) const { return counts_[static_cast<size_t>(joint)]; }

 private:
  Eigen::VectorXd low_;   // per joint: the first bin's lower edge
  double log_step_ = 0.0;  // ln of the ratio of successive edges
  // Per joint: kHistogramBins + 2 counts (below the range, bins, above).
  std::vector<std::vector<Eigen::Index>> bins_;
  std::vector<Eigen::Index> counts_;
  int n_parameters_ = 0;
  bool sums_ = true;
  // Per joint: its columns, and the sums over its columns (c × c).
  std::vector<std::vector<int>> columns_;
  std::vector<Eigen::MatrixXd> hessian_, omega_;  // lower triangles
};

}  // namespace idbench
