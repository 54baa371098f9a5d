#include "idbench/ident/residual_covariance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace idbench {
namespace {

// The summary of batch-means scores, n_eff = n · the median of the ratios
// (σ_white,k / σ_k)² (reordered).
CovarianceSummary Summarise(const ScoreBatchMeans& scores, std::vector<double>* ratios) {
  CovarianceSummary summary;
  summary.method = CovarianceMethod::kBatchMeans;
  summary.n_samples = scores.n_samples();
  summary.block_samples = scores.block_samples();
  summary.n_blocks = scores.n_blocks();
  double median = 1.0;
  if (!ratios->empty()) {
    const size_t h = ratios->size() / 2;
    std::nth_element(ratios->begin(), ratios->begin() + static_cast<std::ptrdiff_t>(h), ratios->end());
    median = (*ratios)[h];
    if (ratios->size() % 2 == 0) {
      median = 0.5 * (median + *std::max_element(ratios->begin(), ratios->begin() + static_cast<std::ptrdiff_t>(h)));
    }
  }
  summary.n_effective = static_cast<double>(scores.n_samples()) * median;
  return summary;
}

}  // namespace

Eigen::Index BatchMeansBlockSamples(Eigen::Index n_samples) {
  if (n_samples <= 1) return 1;
  auto block = static_cast<Eigen::Index>(std::ceil(std::sqrt(static_cast<double>(n_samples))));
  while (block > 1 && (block - 1) * (block - 1) >= n_samples) --block;  // rounding of sqrt
  return block;
}

ScoreBatchMeans::ScoreBatchMeans(int n_parameters, Eigen::Index n_samples, Eigen::Index block_samples,
                                 BlockBias bias)
    : n_samples_(n_samples), automatic_(block_samples == 0), bias_(bias) {
  if (n_parameters < 1 || n_samples < 1 || block_samples < 0) {
    throw std::invalid_argument("batch means: expected n_parameters >= 1, n_samples >= 1 and block_samples >= 0, got " +
                                std::to_string(n_parameters) + ", " + std::to_string(n_samples) + ", " +
                                std::to_string(block_samples));
  }
  auto add = [&](Eigen::Index block) {
    Blocks blocks;
    blocks.block = block;
    blocks.block_sum = Eigen::VectorXd::Zero(n_parameters);
    blocks.sum = Eigen::MatrixXd::Zero(n_parameters, n_parameters);
    lengths_.push_back(std::move(blocks));
  };
  add(automatic_ ? BatchMeansBlockSamples(n_samples) : block_samples);
  while (automatic_ && n_samples / (2 * lengths_.back().block) >= kMinAutoBlocks) add(2 * lengths_.back().block);
  previous_ = c0_ = c1_ = Eigen::VectorXd::Zero(n_parameters);
}

void ScoreBatchMeans::Push(const Eigen::Ref<const Eigen::VectorXd>& score) {
  if (score.size() != previous_.size() || n_pushed_ >= n_samples_) {
    throw std::invalid_argument("batch means: expected a score of " + std::to_string(previous_.size()) +
                                " entries and at most " + std::to_string(n_samples_) + " samples, got " +
                                std::to_string(score.size()) + " entries for sample " + std::to_string(n_pushed_ + 1));
  }
  if (!series_start_) c1_ += score.cwiseProduct(previous_);
  series_start_ = false;
  c0_ += score.cwiseAbs2();
  previous_ = score;
  ++n_pushed_;
  for (Blocks& blocks : lengths_) {
    blocks.block_sum += score;
    // A block complete: its sum's outer product into the total.
    if (++blocks.in_block == blocks.block) {
      blocks.sum.selfadjointView<Eigen::Lower>().rankUpdate(blocks.block_sum);
      blocks.block_sum.setZero();
      blocks.in_block = 0;
      ++blocks.n_blocks;
    }
  }
}

void ScoreBatchMeans::EndSeries() {
  series_start_ = true;
  for (Blocks& blocks : lengths_) {
    if (blocks.in_block == 0) continue;
    blocks.sum.selfadjointView<Eigen::Lower>().rankUpdate(blocks.block_sum);
    blocks.block_sum.setZero();
    blocks.in_block = 0;
    ++blocks.n_blocks;
  }
}

double ScoreBatchMeans::andrews_block_samples() const {
  if (!automatic_ || n_pushed_ < 2) return 0.0;
  double alpha = 0.0;
  int counted = 0;
  for (Eigen::Index k = 0; k < c0_.size(); ++k) {
    if (!(c0_[k] > 0.0)) continue;  // a component that is zero throughout says nothing
    const double rho = std::clamp(c1_[k] / c0_[k], 0.0, 1.0 - 1e-9);
    alpha += 4.0 * rho * rho / ((1.0 - rho) * (1.0 - rho) * (1.0 + rho) * (1.0 + rho));
    ++counted;
  }
  if (counted == 0) return 0.0;
  alpha /= counted;
  return 1.1447 * std::cbrt(alpha * static_cast<double>(n_pushed_));
}

const ScoreBatchMeans::Blocks& ScoreBatchMeans::Chosen() const {
  if (!done() || lengths_.size() == 1) return lengths_.front();
  if (Extrapolated()) return lengths_.back();
  const double wanted = andrews_block_samples();
  for (const Blocks& blocks : lengths_) {
    if (static_cast<double>(blocks.block) >= wanted) return blocks;
  }
  return lengths_.back();
}

Eigen::MatrixXd ScoreBatchMeans::BlockOmega(const Blocks& blocks) {
  const Eigen::Index B = blocks.n_blocks + (blocks.in_block > 0 ? 1 : 0);
  Eigen::MatrixXd sum = blocks.sum;
  if (blocks.in_block > 0) sum.selfadjointView<Eigen::Lower>().rankUpdate(blocks.block_sum);  // the shorter last block
  Eigen::MatrixXd omega = sum.selfadjointView<Eigen::Lower>();
  return omega * (static_cast<double>(B) / static_cast<double>(B - 1));
}

double ScoreBatchMeans::block_bias_factor() const {
  if (!done() || !Extrapolated()) return 1.0;
  // f = 2 − median_k Ω_kk(L) / Ω_kk(2L) over the components not zero throughout.
  const Blocks& longer = lengths_.back();
  const Blocks& shorter = lengths_[lengths_.size() - 2];
  const Eigen::VectorXd d_long = BlockOmega(longer).diagonal(), d_short = BlockOmega(shorter).diagonal();
  std::vector<double> ratios;
  for (Eigen::Index k = 0; k < d_long.size(); ++k) {
    if (d_long[k] > 0.0) ratios.push_back(d_short[k] / d_long[k]);
  }
  if (ratios.empty()) return 1.0;
  std::sort(ratios.begin(), ratios.end());
  const size_t h = ratios.size() / 2;
  const double median = ratios.size() % 2 == 1 ? ratios[h] : 0.5 * (ratios[h - 1] + ratios[h]);
  return std::clamp(2.0 - median, 0.1, 2.0);
}

Eigen::MatrixXd ScoreBatchMeans::Omega() const {
  const Eigen::Index B = n_blocks();
  if (!done() || B < 2) {
    throw std::invalid_argument("batch means: expected " + std::to_string(n_samples_) + " samples in at least 2 blocks, got " +
                                std::to_string(n_pushed_) + " samples in " + std::to_string(B));
  }
  return block_bias_factor() * BlockOmega(Chosen());
}

void PushStackedScores(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof, const LinearFit& fit,
                       ScoreBatchMeans* scores) {
  if (n_dof < 1 || W.rows() != tau.size() || W.rows() % n_dof != 0 || W.cols() != fit.beta.size() ||
      fit.row_weights.size() != n_dof) {
    throw std::invalid_argument("stacked scores: expected W of " + std::to_string(fit.beta.size()) + " columns, tau of " +
                                std::to_string(W.rows()) + " rows, n_dof " + std::to_string(fit.row_weights.size()) +
                                ", got " + std::to_string(W.cols()) + ", " + std::to_string(tau.size()) + ", " +
                                std::to_string(n_dof));
  }
  const Eigen::VectorXd e = tau - W * fit.beta;
  const Eigen::VectorXd e_weights = fit.row_reweighting ? Eigen::VectorXd(tau - W * fit.row_reweighting->beta) : e;
  Eigen::VectorXd score(W.cols());
  for (Eigen::Index s = 0; s < W.rows() / n_dof; ++s) {
    score.setZero();
    if (fit.score_offset.size() > 0) score = fit.score_offset;
    for (int j = 0; j < n_dof; ++j) {
      const Eigen::Index row = s * n_dof + j;
      score += (ScoreRowWeight(fit, j, e_weights[row]) * e[row]) * W.row(row).transpose();
    }
    scores->Push(score);
  }
}

void ApplyScoreCovariance(const ScoreBatchMeans& scores, LinearFit* fit) {
  const Eigen::Index p = fit->beta.size();
  if (fit->gram_inverse.rows() != p || fit->gram_inverse.cols() != p) {
    throw std::invalid_argument("score covariance: the fit has no (WᵀW)⁻¹ of " + std::to_string(p) + " parameters");
  }
  if (scores.done() && scores.n_blocks() < 2) return;  // too few samples to say more than the white formula
  const Eigen::MatrixXd omega = scores.Omega();
  if (omega.rows() != p) {
    throw std::invalid_argument("score covariance: expected scores of " + std::to_string(p) + " parameters, got " +
                                std::to_string(omega.rows()));
  }
  // The sandwich G Ω G.
  const Eigen::MatrixXd& G = fit->gram_inverse;
  fit->covariance = G * omega * G;
  fit->covariance = 0.5 * (fit->covariance + fit->covariance.transpose()).eval();
  fit->sigma = fit->covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  std::vector<double> ratios;  // (σ_white,k / σ_k)² of the identifiable parameters
  for (Eigen::Index k = 0; k < p; ++k) {
    if (!fit->identifiable[static_cast<size_t>(k)]) {
      fit->sigma[k] = std::numeric_limits<double>::infinity();
    } else if (fit->sigma[k] > 0.0 && std::isfinite(fit->sigma_white[k])) {
      ratios.push_back(fit->sigma_white[k] * fit->sigma_white[k] / (fit->sigma[k] * fit->sigma[k]));
    }
  }
  fit->rel_sigma_percent = 100.0 * fit->sigma.cwiseQuotient(fit->beta.cwiseAbs());
  fit->covariance_method = Summarise(scores, &ratios);
}

namespace {

// B Ω Bᵀ from the scores Z_tᵀ e_t (B Ω B when b_symmetric: the least-squares
// G, multiplied as it always was); white: the white-residual covariance, for
// the summary and for too few samples.
Eigen::MatrixXd ScoreSandwich(const Eigen::MatrixXd& Z, const Eigen::VectorXd& residual, int n_dof,
                              const Eigen::MatrixXd& B, bool b_symmetric, const Eigen::MatrixXd& white,
                              CovarianceSummary* summary, BlockBias bias) {
  const Eigen::Index p = Z.cols();
  if (n_dof < 1 || Z.rows() != residual.size() || Z.rows() % n_dof != 0 || B.rows() != p || B.cols() != p ||
      white.rows() != p || white.cols() != p) {
    throw std::invalid_argument("stacked sandwich: expected A with whole samples of " + std::to_string(n_dof) +
                                " rows, a residual of its rows and G of " + std::to_string(p) + " x " +
                                std::to_string(p) + ", got " + std::to_string(Z.rows()) + " x " +
                                std::to_string(p) + ", " + std::to_string(residual.size()) + ", " +
                                std::to_string(B.rows()) + " x " + std::to_string(B.cols()));
  }
  const Eigen::Index n = Z.rows() / n_dof;
  if (n < 1 || p < 1 || BatchMeansBlockSamples(n) >= n) {  // fewer than 2 blocks: the white formula
    if (summary) *summary = CovarianceSummary{CovarianceMethod::kWhite, n, 0, 0, static_cast<double>(n)};
    return white;
  }
  ScoreBatchMeans scores(static_cast<int>(p), n, 0, bias);
  for (Eigen::Index t = 0; t < n; ++t) {
    scores.Push(Z.middleRows(t * n_dof, n_dof).transpose() * residual.segment(t * n_dof, n_dof));
  }
  Eigen::MatrixXd covariance = b_symmetric ? Eigen::MatrixXd(B * scores.Omega() * B)
                                           : Eigen::MatrixXd(B * scores.Omega() * B.transpose());
  covariance = 0.5 * (covariance + covariance.transpose()).eval();
  if (summary) {
    std::vector<double> ratios;
    for (Eigen::Index k = 0; k < p; ++k) {
      if (white(k, k) > 0.0 && covariance(k, k) > 0.0) ratios.push_back(white(k, k) / covariance(k, k));
    }
    *summary = Summarise(scores, &ratios);
  }
  return covariance;
}

}  // namespace

Eigen::MatrixXd StackedSandwichCovariance(const Eigen::MatrixXd& A, const Eigen::VectorXd& residual, int n_dof,
                                          const Eigen::MatrixXd& G, double sigma2, CovarianceSummary* summary) {
  return ScoreSandwich(A, residual, n_dof, G, true, sigma2 * G, summary, BlockBias::kAsIs);
}

Eigen::MatrixXd StackedInstrumentSandwich(const Eigen::MatrixXd& Z, const Eigen::VectorXd& residual, int n_dof,
                                          const Eigen::MatrixXd& B, const Eigen::MatrixXd& white,
                                          CovarianceSummary* summary, BlockBias bias) {
  return ScoreSandwich(Z, residual, n_dof, B, false, white, summary, bias);
}

void ApplyStackedScoreCovariance(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof, LinearFit* fit,
                                 Eigen::Index block_samples, BlockBias bias) {
  if (n_dof < 1) throw std::invalid_argument("stacked scores: expected n_dof >= 1, got " + std::to_string(n_dof));
  ScoreBatchMeans scores(static_cast<int>(W.cols()), W.rows() / n_dof, block_samples, bias);
  PushStackedScores(W, tau, n_dof, *fit, &scores);
  ApplyScoreCovariance(scores, fit);
}

}  // namespace idbench
