#include "idbench/ident/robust_weights.h"

#include <algorithm>
#include <cmath>

namespace idbench {

namespace {
// The histogram's range relative to the joint's reference RMS: the median of
// |r| is at most √2 × its RMS (Markov), and below 10⁻¹² of it lies rounding.
constexpr double kHistogramLow = 1e-12;
constexpr double kHistogramHigh = 1e4;
}  // namespace

double DefaultTuning(RobustLoss loss) { return loss == RobustLoss::kHuber ? 1.345 : 4.685; }

IrlsPassRecord::IrlsPassRecord(const Eigen::VectorXd& reference, int n_parameters)
    : low_(reference.cwiseMax(1e-300) * kHistogramLow),
      log_step_(std::log(kHistogramHigh / kHistogramLow) / kHistogramBins),
      bins_(static_cast<size_t>(reference.size()), std::vector<Eigen::Index>(kHistogramBins + 2, 0)),
      counts_(static_cast<size_t>(reference.size()), 0),
      hessian_(static_cast<size_t>(reference.size()), Eigen::MatrixXd::Zero(n_parameters, n_parameters)),
      omega_(hessian_) {}

void IrlsPassRecord::Add(int joint, double residual,
                         const Eigen::Ref<const Eigen::RowVectorXd, 0, Eigen::InnerStride<>>& x,
                         const std::vector<int>& columns, const RobustRowWeights& weights) {
  Add(joint, residual);
  const double slope = weights.Slope(joint, residual);
  const double wr = weights.Weight(joint, residual) * residual;
  Eigen::MatrixXd& H = hessian_[static_cast<size_t>(joint)];
  Eigen::MatrixXd& O = omega_[static_cast<size_t>(joint)];
  const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
  for (Eigen::Index b = 0; b < c; ++b) {
    const int cb = columns[static_cast<size_t>(b)];
    for (Eigen::Index a = b; a < c; ++a) {  // columns ascending: (ca, cb) in the lower triangle
      const int ca = columns[static_cast<size_t>(a)];
      const double xx = x[a] * x[b];
      H(ca, cb) += slope * xx;
      O(ca, cb) += wr * wr * xx;
    }
  }
}

namespace {
Eigen::MatrixXd SumLower(const std::vector<Eigen::MatrixXd>& per_joint) {
  Eigen::MatrixXd sum = per_joint.front();
  for (size_t j = 1; j < per_joint.size(); ++j) sum += per_joint[j];
  return sum.selfadjointView<Eigen::Lower>();
}
}  // namespace

Eigen::MatrixXd IrlsPassRecord::Hessian() const { return SumLower(hessian_); }
Eigen::MatrixXd IrlsPassRecord::WhiteScoreCovariance() const { return SumLower(omega_); }

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
