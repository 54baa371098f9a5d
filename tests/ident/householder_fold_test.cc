// The fold kernel of the streamed least squares: both of its builds give the
// R factor of [T; A] (RᵀR = [T; A]ᵀ[T; A]) and agree with each other.
#include "householder_fold.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <random>

#include "engine/test_util.h"

namespace idbench::internal {
namespace {

using Kernel = std::function<void(double*, std::ptrdiff_t, double*, std::ptrdiff_t, std::ptrdiff_t,
                                  std::ptrdiff_t)>;

// Folds A's rows into T in blocks of `block` rows; returns the final T.
Eigen::MatrixXd FoldInBlocks(const Kernel& kernel, const Eigen::MatrixXd& T0, const Eigen::MatrixXd& A,
                             Eigen::Index block) {
  Eigen::MatrixXd T = T0;
  for (Eigen::Index r0 = 0; r0 < A.rows(); r0 += block) {
    Eigen::MatrixXd rows = A.middleRows(r0, std::min(block, A.rows() - r0));
    kernel(T.data(), T.outerStride(), rows.data(), rows.outerStride(), rows.rows(), T.cols());
  }
  return T;
}

TEST(HouseholderFoldTest, BothBuildsGiveTheQrFactor) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::pair<const char*, Kernel>> kernels = {{"baseline", FoldRowsIntoTriangleBaseline},
                                                         {"dispatched", FoldRowsIntoTriangle}};
#if defined(__x86_64__)
  if (HasFoldX86V3()) kernels.emplace_back("x86-64-v3", FoldRowsIntoTriangleX86V3);
#endif
  // Columns: inside one panel, exactly two panels, partial last panel (39, as
  // puma560's joint 1); rows: blocks that are and are not multiples of 4.
  for (int n : {3, 16, 39}) {
    for (Eigen::Index block : {1, 7, 128}) {
      const Eigen::MatrixXd T0 = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); })
                                     .triangularView<Eigen::Upper>();
      Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(301, n, [&] { return u(rng); });
      if (n > 10) A.col(10).setZero();  // a reflection that is the identity, inside a panel
      Eigen::MatrixXd TA(n + A.rows(), n);
      TA << T0, A;
      const Eigen::MatrixXd gram = TA.transpose() * TA;
      Eigen::MatrixXd first;
      for (const auto& [name, kernel] : kernels) {
        SCOPED_TRACE(std::string(name) + ", " + std::to_string(n) + " columns, blocks of " + std::to_string(block));
        const Eigen::MatrixXd T = FoldInBlocks(kernel, T0, A, block);
        EXPECT_TRUE(T.isUpperTriangular(0.0));
        EXPECT_LT(testing::RelativeError(Eigen::MatrixXd(T.transpose() * T), gram), 1e-13);
        if (first.size() == 0) first = T;
        EXPECT_LT(testing::RelativeError(T, first), 1e-12);  // same signs: the same R
      }
    }
  }
}

}  // namespace
}  // namespace idbench::internal
