// The inner kernel of the streamed least squares (linear_estimator.h): fold
// rows into an upper-triangular factor by Householder reflections.
#pragma once

#include <cstddef>

namespace idbench::internal {

// Replaces T by the R factor of [T; A]: T (n × n, upper triangular, column
// major, leading dimension ldt) and A (m × n, column major, leading dimension
// lda), so that [T; A]ᵀ[T; A] = T'ᵀT'. T's zeros below the diagonal stay zero;
// A is overwritten (the reflections' vectors). Blocked in panels of 8 columns
// (compact WY, Schreiber & Van Loan 1989; LAPACK dgeqrt/dtpqrt).
//
// Built twice, for x86-64-v3 (AVX2 + FMA) and the baseline; the x86-64-v3
// build runs where the CPU has it, so results differ between machines by
// rounding only.
void FoldRowsIntoTriangle(double* T, std::ptrdiff_t ldt, double* A, std::ptrdiff_t lda, std::ptrdiff_t m,
                          std::ptrdiff_t n);

// The two builds, for tests: the baseline runs anywhere; the x86-64-v3 one
// only where HasFoldX86V3().
void FoldRowsIntoTriangleBaseline(double* T, std::ptrdiff_t ldt, double* A, std::ptrdiff_t lda, std::ptrdiff_t m,
                                  std::ptrdiff_t n);
bool HasFoldX86V3();
#if defined(__x86_64__)
void FoldRowsIntoTriangleX86V3(double* T, std::ptrdiff_t ldt, double* A, std::ptrdiff_t lda, std::ptrdiff_t m,
                               std::ptrdiff_t n);
#endif

}  // namespace idbench::internal
