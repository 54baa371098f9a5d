#include "householder_fold.h"

#include <algorithm>
#include <cmath>
#include <cstring>

// Plain loops over GCC vector types (4 doubles): one AVX2 register in the
// x86-64-v3 build, two SSE2 registers in the baseline one. This file is
// compiled with -ffp-contract=fast, so a·b + c becomes an FMA where the CPU
// has it.
namespace idbench::internal {
namespace {

using Index = std::ptrdiff_t;
using Vec = double __attribute__((vector_size(32)));
constexpr Index kLanes = 4;
constexpr Index kPanel = 8;  // reflections applied at once to the columns right of a panel

[[gnu::always_inline]] inline Vec Load(const double* p) {
  Vec v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void Store(double* p, const Vec& v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline double Sum(const Vec& v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// xᵀy over m entries.
[[gnu::always_inline]] inline double Dot(const double* x, const double* y, Index m) {
  Vec s0 = {}, s1 = {};
  Index i = 0;
  for (; i + 2 * kLanes <= m; i += 2 * kLanes) {
    s0 += Load(x + i) * Load(y + i);
    s1 += Load(x + i + kLanes) * Load(y + i + kLanes);
  }
  for (; i + kLanes <= m; i += kLanes) s0 += Load(x + i) * Load(y + i);
  double s = Sum(s0 + s1);
  for (; i < m; ++i) s += x[i] * y[i];
  return s;
}

// y −= a x over m entries.
[[gnu::always_inline]] inline void SubtractScaled(double a, const double* x, double* y, Index m) {
  Index i = 0;
  for (; i + kLanes <= m; i += kLanes) Store(y + i, Load(y + i) - a * Load(x + i));
  for (; i < m; ++i) y[i] -= a * x[i];
}

// out[k] = V(:, k)ᵀ a for the kPanel columns of V (m rows, leading dimension
// lda): one pass over a.
[[gnu::always_inline]] inline void PanelDots(const double* V, Index lda, const double* a, Index m, double* out) {
  Vec s[kPanel] = {};  // in registers once the loops below are unrolled
  Index i = 0;
  for (; i + kLanes <= m; i += kLanes) {
    const Vec ai = Load(a + i);
#pragma GCC unroll 8
    for (Index k = 0; k < kPanel; ++k) s[k] += Load(V + k * lda + i) * ai;
  }
  for (Index k = 0; k < kPanel; ++k) {
    out[k] = Sum(s[k]);
    for (Index r = i; r < m; ++r) out[k] += V[k * lda + r] * a[r];
  }
}

// a −= V y for the kPanel columns of V: one pass over a.
[[gnu::always_inline]] inline void PanelUpdate(const double* V, Index lda, const double* y, double* a, Index m) {
  Index i = 0;
  for (; i + kLanes <= m; i += kLanes) {
    Vec ai = Load(a + i);
#pragma GCC unroll 8
    for (Index k = 0; k < kPanel; ++k) ai -= Load(V + k * lda + i) * y[k];
    Store(a + i, ai);
  }
  for (; i < m; ++i) {
    for (Index k = 0; k < kPanel; ++k) a[i] -= V[k * lda + i] * y[k];
  }
}

// The kernel, inlined into each build below.
[[gnu::always_inline]] inline void Fold(double* T, Index ldt, double* A, Index lda, Index m, Index n) {
  auto t = [&](Index row, Index col) -> double& { return T[row + col * ldt]; };
  for (Index k0 = 0; k0 < n; k0 += kPanel) {
    const Index bs = std::min(kPanel, n - k0);
    // 1. The panel's reflections, each applied to the panel columns right of
    //    it. Column k's reflection H_k = 𝟙 − τ_k v vᵀ, v = [e_k; x/(T_kk − β)]
    //    (x: column k of A), maps [T_kk; x] onto [β; 0] (LAPACK dlarfg); v's
    //    tail is kept in place of x.
    double tau[kPanel] = {};
    for (Index k = k0; k < k0 + bs; ++k) {
      double* x = A + k * lda;
      const double x2 = Dot(x, x, m);
      if (x2 == 0.0) continue;  // τ_k = 0, v = e_k
      const double alpha = t(k, k);
      const double beta = -std::copysign(std::sqrt(alpha * alpha + x2), alpha);
      tau[k - k0] = (beta - alpha) / beta;
      const double scale = 1.0 / (alpha - beta);
      for (Index i = 0; i < m; ++i) x[i] *= scale;
      t(k, k) = beta;
      for (Index c = k + 1; c < k0 + bs; ++c) {
        double* a = A + c * lda;
        const double w = tau[k - k0] * (t(k, c) + Dot(x, a, m));
        t(k, c) -= w;
        SubtractScaled(w, x, a, m);
      }
    }
    if (k0 + bs == n) break;  // no columns right of the panel; below, bs = kPanel
    // 2. H_k0 ⋯ H_k0+7 = 𝟙 − V W Vᵀ, W upper triangular (LAPACK dlarft):
    //    column i is −τ_i W(0:i, 0:i) Vᵀ v_i above τ_i (the e_k parts of V are
    //    orthogonal, so Vᵀ v_i needs only the tails in A). W[col][row].
    const double* V = A + k0 * lda;
    double W[kPanel][kPanel] = {};
    for (Index i = 0; i < kPanel; ++i) W[i][i] = tau[i];
    for (Index i = 1; i < kPanel; ++i) {
      if (tau[i] == 0.0) continue;
      double y[kPanel];
      PanelDots(V, lda, V + i * lda, m, y);
      for (Index r = 0; r < i; ++r) {
        double s = 0.0;
        for (Index l = r; l < i; ++l) s += W[l][r] * y[l];
        W[i][r] = -tau[i] * s;
      }
    }
    // 3. (𝟙 − V Wᵀ Vᵀ) on each column right of the panel: its entries in the
    //    panel's rows of T, and in A.
    for (Index c = k0 + kPanel; c < n; ++c) {
      double* a = A + c * lda;
      double y1[kPanel], y2[kPanel];
      PanelDots(V, lda, a, m, y1);
      for (Index k = 0; k < kPanel; ++k) y1[k] += t(k0 + k, c);
      for (Index k = 0; k < kPanel; ++k) {
        double s = 0.0;
        for (Index r = 0; r <= k; ++r) s += W[k][r] * y1[r];
        y2[k] = s;
        t(k0 + k, c) -= s;
      }
      PanelUpdate(V, lda, y2, a, m);
    }
  }
}

}  // namespace

void FoldRowsIntoTriangleBaseline(double* T, Index ldt, double* A, Index lda, Index m, Index n) {
  Fold(T, ldt, A, lda, m, n);
}

#if defined(__x86_64__)
[[gnu::target("arch=x86-64-v3")]] void FoldRowsIntoTriangleX86V3(double* T, Index ldt, double* A, Index lda,
                                                                 Index m, Index n) {
  Fold(T, ldt, A, lda, m, n);
}
#endif

bool HasFoldX86V3() {
#if defined(__x86_64__)
#if defined(__clang__)
  // clang 16 (the sanitizer build) has no "x86-64-v3" here: the parts of it
  // the compiled kernel uses (AVX, AVX2, FMA, BMI1/2).
  static const bool supported = __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
                                __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                                __builtin_cpu_supports("bmi2");
#else
  static const bool supported = __builtin_cpu_supports("x86-64-v3");
#endif
  return supported;
#else
  return false;
#endif
}

void FoldRowsIntoTriangle(double* T, Index ldt, double* A, Index lda, Index m, Index n) {
#if defined(__x86_64__)
  if (HasFoldX86V3()) return FoldRowsIntoTriangleX86V3(T, ldt, A, lda, m, n);
#endif
  FoldRowsIntoTriangleBaseline(T, ldt, A, lda, m, n);
}

}  // namespace idbench::internal
