#include "idbench/ident/robust_weights.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace idbench {

namespace {
// The histogram's range relative to the joint's reference RMS: the median of
// |r| is at most √2 × its RMS (Markov), and below 10⁻¹² of it lies rounding.
constexpr double kHistogramLow = 1e-12;
constexpr double kHistogramHigh = 1e4;
}  // namespace

double DefaultTuning(RobustLoss loss) { return loss == RobustLoss::kHuber ? 1.345 : 4.685; }

IrlsPassRecord::IrlsPassRecord(const Eigen::VectorXd& reference, int n_parameters, bool sums)
    : low_(reference.cwiseMax(1e-300) * kHistogramLow),
      log_step_(std::log(kHistogramHigh / kHistogramLow) / kHistogramBins),
      bins_(static_cast<size_t>(reference.size()), std::vector<Eigen::Index>(kHistogramBins + 2, 0)),
      counts_(static_cast<size_t>(reference.size()), 0),
      n_parameters_(n_parameters),
      sums_(sums),
      columns_(static_cast<size_t>(reference.size())),
      hessian_(static_cast<size_t>(reference.size())),
      omega_(hessian_) {}

void IrlsPassRecord::AddRows(int joint, const Eigen::Ref<const Eigen::VectorXd>& residuals,
                             const Eigen::Ref<const Eigen::MatrixXd>& x, const std::vector<int>& columns,
                             const RobustRowWeights& weights) {
  if (!sums_) {
    for (Eigen::Index i = 0; i < residuals.size(); ++i) Add(joint, residuals[i]);
    return;
  }
  const size_t j = static_cast<size_t>(joint);
  const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
  if (hessian_[j].size() == 0) {
    columns_[j] = columns;
    hessian_[j] = Eigen::MatrixXd::Zero(c, c);
    omega_[j] = Eigen::MatrixXd::Zero(c, c);
  } else if (columns_[j] != columns) {
    throw std::logic_error("IrlsPassRecord: joint " + std::to_string(joint) + "'s columns changed between calls");
  }
  const Eigen::Index m = residuals.size();
  Eigen::VectorXd slope(m), wr2(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const double r = residuals[i];
    Add(joint, r);
    slope[i] = weights.Slope(joint, r);
    const double wr = weights.Weight(joint, r) * r;
    wr2[i] = wr * wr;
  }
  // Σ ψ'/s² x xᵀ and Σ (w r)² x xᵀ over the rows: Xᵀ diag(d) X, lower
  // triangles only.
  Eigen::MatrixXd scaled = slope.asDiagonal() * x;
  hessian_[j].triangularView<Eigen::Lower>() += x.transpose() * scaled;
  scaled = wr2.asDiagonal() * x;
  omega_[j].triangularView<Eigen::Lower>() += x.transpose() * scaled;
}

namespace {
// Σ over joints of each joint's sums, placed at its columns (p × p).
Eigen::MatrixXd SumOverJoints(const std::vector<Eigen::MatrixXd>& per_joint,
                              const std::vector<std::vector<int>>& columns, int n_parameters) {
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n_parameters, n_parameters);
  for (size_t j = 0; j < per_joint.size(); ++j) {
    const std::vector<int>& at = columns[j];
    for (size_t b = 0; b < at.size(); ++b) {
      for (size_t a = 0; a < at.size(); ++a) {
        // The lower triangle holds the sums (columns ascending).
        const Eigen::Index lo = static_cast<Eigen::Index>(std::max(a, b)), hi = static_cast<Eigen::Index>(std::min(a, b));
        sum(at[a], at[b]) += per_joint[j](lo, hi);
      }
    }
  }
  return sum;
}
}  // namespace

Eigen::MatrixXd IrlsPassRecord::Hessian() const { return SumOverJoints(hessian_, columns_, n_parameters_); }
Eigen::MatrixXd IrlsPassRecord::WhiteScoreCovariance() const {
  return SumOverJoints(omega_, columns_, n_parameters_);
}

void IrlsPassRecord::Add(int joint, double residual) {
  const double a = std::abs(residual);
  const double x = std::log(a / low_[joint]) / log_step_;  // -inf for a = 0
  Eigen::Index bin = 0;                                    // below the range
  if (x >= kHistogramBins) bin = kHistogramBins + 1;       // above it (or NaN: counted high)
  else if (x >= 0.0) bin = 1 + static_cast<Eigen::Index>(x);
  else if (std::isnan(x)) bin = kHistogramBins + 1;
  ++bins_[static_cast<size_t>(joint)][static_cast<size_t>(bin)];
  ++counts_[static_cast<size_t>(joint)];
}

Eigen::VectorXd IrlsPassRecord::Median() const {
  Eigen::VectorXd median = Eigen::VectorXd::Zero(low_.size());
  for (Eigen::Index j = 0; j < low_.size(); ++j) {
    const std::vector<Eigen::Index>& bins = bins_[static_cast<size_t>(j)];
    const double half = 0.5 * static_cast<double>(counts_[static_cast<size_t>(j)]);
    if (half == 0.0) continue;
    // The bin where the cumulative count passes half, the median placed in it
    // log-linearly by the fraction of its count needed.
    double below = 0.0;
    for (size_t b = 0; b < bins.size(); ++b) {
      const double in = static_cast<double>(bins[b]);
      if (below + in < half) {
        below += in;
        continue;
      }
      if (b == 0) median[j] = low_[j];  // rounding-level residuals: the floor of the range
      else if (b == bins.size() - 1) median[j] = low_[j] * std::exp(log_step_ * kHistogramBins);
      else median[j] = low_[j] * std::exp(log_step_ * (static_cast<double>(b - 1) + (half - below) / in));
      break;
    }
  }
  return median;
}

}  // namespace idbench
