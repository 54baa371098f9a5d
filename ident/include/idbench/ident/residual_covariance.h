// σ from the residual as it is (issue 34): a covariance of the least-squares
// estimate that holds when the residual is coloured (filtered signals,
// unmodelled dynamics) and of a different size on every joint, where
// s² (WᵀW)⁻¹ assumes it white and of one variance.
//
// The estimate is β̂ = G W̃ᵀ τ̃ with W̃, τ̃ the rows weighted per joint (w_j:
// 1 for OLS, 1/σ_j for WLS) and G = (W̃ᵀW̃)⁻¹, so β̂ − β = G Σ_t s_t with the
// per-sample score
//   s_t = Σ_j w_j² W_tjᵀ e_tj   (p),
// all joints of instant t summed, so that their correlation at one instant
// is kept. Its covariance is the sandwich
//   cov = G Ω G,   Ω = Var(Σ_t s_t).
// Ω by non-overlapping batch means (Conway 1963; Flegal & Jones 2010, Ann.
// Statist. 38(2)): the n samples cut into blocks of L consecutive samples,
// S_b = Σ_{t∈b} s_t at the fitted β̂ (the residual e = τ − W β̂), and
//   Ω = B/(B − 1) Σ_b S_b S_bᵀ     (B blocks).
// Correlation within a block is counted in full, across blocks only at their
// boundaries: its expectation weights lag ℓ by (1 − ℓ/L), Newey–West's
// Bartlett kernel with bandwidth L, so Ω is short by about 2 Σ_ℓ ℓ γ_ℓ / L:
// L must be long against the residual's correlation time. B/(B − 1) undoes
// the shrinkage of Σ_b S_b S_bᵀ by the fitted β̂ (Σ_t s_t = 0 at β̂: for white
// noise and similar blocks, E Σ_b S_b S_bᵀ = (1 − 1/B) σ² W̃ᵀW̃).
// The block length: at least L₀ = ⌈√n⌉ (the standard consistent batch size),
// longer when the scores are strongly correlated: Andrews' (1991,
// Econometrica 59(3)) AR(1) plug-in bandwidth for the Bartlett kernel,
//   L_A = 1.1447 (α n)^{1/3},  α = mean_k 4ρ_k² / ((1 − ρ_k)² (1 + ρ_k)²),
// ρ_k the lag-1 autocorrelation of score component k (each component
// weighted alike, whatever its scale; ρ_k < 0 counts as 0). The blocks are
// summed at L₀, 2L₀, 4L₀, … (while they give at least kMinAutoBlocks
// blocks) in the same pass, and the shortest of those ≥ L_A is used (the
// longest when none is). Measured on AR(1) noise of ρ = 0.97 over 10 000
// samples, 400 draws (tests/ident/residual_covariance_test.cc): L₀ = 100
// gives σ 0.80–0.86 of the spread of the estimates, the chosen 400 0.90–0.98.
// It needs only running block sums and p × p accumulators per length:
// memory O(p² log n), whatever the log's length.
//
// Scores whose spectrum nearly vanishes at zero frequency (the residual of
// the closed-loop estimators, IV and DIDIM, is mostly the loop's reaction to
// the position noise: about M × its second derivative below the loop's
// bandwidth) have a long-run variance far below their short-lag variance:
// Σ_ℓ ℓ γ_ℓ < 0, and batch means over-estimate Ω by about −2 Σ_ℓ ℓ γ_ℓ / L,
// which a longer block only shrinks as 1/L (measured on table_arm under a PID,
// BENCHMARKS.md: σ² / spread² = 1 + 3.5 · 95/L for L = 95 … 1800). The
// extrapolated estimate (BlockBias::kExtrapolated) removes that 1/L term, as
// the flat-top batch means 2 Ω(2L) − Ω(L) do (Vats & Flegal 2022,
// Biometrika 109(3), "lugsail" with r = 2, c = 1/2), but with one factor for
// all of Ω so that it stays positive semi-definite and steady on logs of
// tens of blocks: with the two longest lengths summed, L and 2L,
//   Ω = f Ω(2L),  f = 2 − median_k Ω_kk(L) / Ω_kk(2L),  f within [0.1, 2]
// (f = Ω∞ / Ω(2L) when Ω(L) = Ω∞ + c/L; 2 − ratio is the flat-top's per
// component). The flat-top per entry, tried, left 10 % of the σ at zero.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "idbench/ident/linear_estimator.h"

namespace idbench {

// ⌈√n⌉, at least 1: the shortest block of batch means for n samples.
Eigen::Index BatchMeansBlockSamples(Eigen::Index n_samples);
// The fewest blocks a longer block length may leave (automatic length).
inline constexpr Eigen::Index kMinAutoBlocks = 20;

// How Ω treats the bias of the block length (above): kAsIs, Ω(L) at the
// length chosen; kExtrapolated, f Ω(2L) from the two longest lengths summed
// (as kAsIs when the length is given or only one length fits).
enum class BlockBias { kAsIs, kExtrapolated };

// The scores of a fit's samples, pushed in time order, summed over blocks.
class ScoreBatchMeans {
 public:
  // p parameters, n_samples that will be pushed, block_samples per block
  // (0: chosen from the scores, above). Throws std::invalid_argument for
  // p < 1, n_samples < 1 or block_samples < 0.
  ScoreBatchMeans(int n_parameters, Eigen::Index n_samples, Eigen::Index block_samples = 0,
                  BlockBias bias = BlockBias::kAsIs);

  // The next sample's score s_t (p). Throws std::invalid_argument on a size
  // mismatch or more samples than announced.
  void Push(const Eigen::Ref<const Eigen::VectorXd>& score);
  // Ends a series (one log of several fitted together): the block being
  // filled is closed, shorter, so that no block straddles two logs, and the
  // next score is not paired with this one in the lag-1 autocorrelation.
  // Independent logs then add their blocks' Σ S_b S_bᵀ. A no-op at a block's
  // end and before the first score.
  void EndSeries();

  bool done() const { return n_pushed_ == n_samples_; }
  Eigen::Index n_samples() const { return n_samples_; }
  // The block length used (before done(): the shortest summed).
  Eigen::Index block_samples() const { return Chosen().block; }
  // Blocks of that length (the last may be shorter); complete once done().
  Eigen::Index n_blocks() const { return Chosen().n_blocks + (Chosen().in_block > 0 ? 1 : 0); }
  // Andrews' L_A from the scores so far (0 before two samples, or when the
  // block length was given).
  double andrews_block_samples() const;
  // B/(B − 1) Σ_b S_b S_bᵀ (p × p), times f when kExtrapolated; requires
  // done() and at least 2 blocks.
  Eigen::MatrixXd Omega() const;
  // kExtrapolated's f (1 otherwise, and before done()).
  double block_bias_factor() const;

 private:
  struct Blocks {                // the sums at one block length
    Eigen::Index block = 1;
    Eigen::Index in_block = 0, n_blocks = 0;
    Eigen::VectorXd block_sum;   // S_b of the block being filled (p)
    Eigen::MatrixXd sum;         // Σ_b S_b S_bᵀ over the completed blocks (p × p)
  };
  const Blocks& Chosen() const;
  bool Extrapolated() const { return bias_ == BlockBias::kExtrapolated && lengths_.size() >= 2; }
  static Eigen::MatrixXd BlockOmega(const Blocks& blocks);  // B/(B − 1) Σ_b S_b S_bᵀ of one length

  Eigen::Index n_samples_;
  Eigen::Index n_pushed_ = 0;
  bool automatic_;
  BlockBias bias_;
  std::vector<Blocks> lengths_;  // L₀, 2L₀, … (one: a given length)
  Eigen::VectorXd previous_, c0_, c1_;  // s_{t−1}; Σ s_t²; Σ s_t s_{t−1} (p)
  bool series_start_ = true;            // the next score starts a series (no s_{t−1})
};

// Adds the scores of dense stacked rows (rows interleaved by joint,
// row = sample·n_dof + joint), one per sample, in order, at fit.beta with
// fit.row_weights. Throws std::invalid_argument on a size mismatch.
void PushStackedScores(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof, const LinearFit& fit,
                       ScoreBatchMeans* scores);

// Replaces fit's covariance, sigma and rel_sigma_percent by the batch-means
// sandwich G Ω G (sigma_white keeps the white-residual σ; not identifiable
// parameters keep σ = ∞) and fills covariance_method. Scores of fewer than
// 2 blocks (n ≤ 2 samples) leave the fit as it is. Throws
// std::invalid_argument unless the scores are complete and of fit's size.
void ApplyScoreCovariance(const ScoreBatchMeans& scores, LinearFit* fit);

// The batch-means sandwich G Ω G of a least-squares solution x of dense
// stacked rows A x ≈ b (row = sample·n_dof + joint; several logs one after
// the other, whole samples each), from its residual e = A x − b and
// G = (AᵀA)⁺ (p × p); Ω from the per-sample scores A_tᵀ e_t. *summary
// (optional) gets the method, blocks and n_eff against the white σ² G_kk
// (sigma2 = ‖e‖²/(m − rank)). Returns sigma2 · G when there are too few
// samples for 2 blocks (summary: kWhite). Throws std::invalid_argument on a
// size mismatch. For estimators that are not LinearFit (payload, gains).
Eigen::MatrixXd StackedSandwichCovariance(const Eigen::MatrixXd& A, const Eigen::VectorXd& residual, int n_dof,
                                          const Eigen::MatrixXd& G, double sigma2, CovarianceSummary* summary);

// The same for an instrumental-variables estimate β̂ = (ZᵀA)⁻¹ Zᵀ b (Z the
// instruments, rows as A's): B Ω Bᵀ with B = (ZᵀA)⁻¹ (p × p), Ω from the
// per-sample scores Z_tᵀ e_t of the residual e = b − A β̂. white: the
// white-residual covariance s² B ZᵀZ Bᵀ, for *summary's n_eff and returned
// when there are too few samples for 2 blocks. Throws as above.
Eigen::MatrixXd StackedInstrumentSandwich(const Eigen::MatrixXd& Z, const Eigen::VectorXd& residual, int n_dof,
                                          const Eigen::MatrixXd& B, const Eigen::MatrixXd& white,
                                          CovarianceSummary* summary, BlockBias bias = BlockBias::kAsIs);

// The batch-means covariance of a fit to dense stacked rows (the rows the
// fit was solved from): PushStackedScores, then ApplyScoreCovariance.
void ApplyStackedScoreCovariance(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof, LinearFit* fit,
                                 Eigen::Index block_samples = 0, BlockBias bias = BlockBias::kAsIs);

}  // namespace idbench
