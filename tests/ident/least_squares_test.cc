#include "idbench/ident/least_squares.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>

namespace idbench {
namespace {

TEST(LeastSquaresTest, FullRankMatchesHouseholderQr) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(40, 5);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(40);
  const LeastSquaresSolution sol = SolveLeastSquares(A, b);
  const Eigen::VectorXd x_qr = A.householderQr().solve(b);
  EXPECT_EQ(sol.rank, 5);
  for (int j = 0; j < 5; ++j) EXPECT_TRUE(sol.identifiable[static_cast<size_t>(j)]);
  EXPECT_LT((sol.x - x_qr).norm(), 1e-12 * x_qr.norm());
  EXPECT_NEAR(sol.residual_norm, (A * x_qr - b).norm(), 1e-12);
}

TEST(LeastSquaresTest, ZeroAndDependentColumnsAreNotIdentifiable) {
  // Columns: x0 free, x1 zero, x2 and x3 only through their sum, x4 free.
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(30, 5);
  A.col(1).setZero();
  A.col(3) = 2.0 * A.col(2);
  const Eigen::VectorXd x_true = (Eigen::VectorXd(5) << 1.5, 7.0, -2.0, 0.5, 3.0).finished();
  const Eigen::VectorXd b = A * x_true;
  const LeastSquaresSolution sol = SolveLeastSquares(A, b, {"a", "b", "c", "d", "e"});
  EXPECT_EQ(sol.rank, 3);
  EXPECT_EQ(sol.identifiable, (std::vector<bool>{true, false, false, false, true}));
  EXPECT_NEAR(sol.x[0], 1.5, 1e-12);
  EXPECT_NEAR(sol.x[4], 3.0, 1e-12);
  EXPECT_TRUE(std::isnan(sol.x[1]) && std::isnan(sol.x[2]) && std::isnan(sol.x[3]));
  EXPECT_NE(sol.reason[1].find("column of b is zero"), std::string::npos) << sol.reason[1];
  EXPECT_NE(sol.reason[2].find("dependent on d"), std::string::npos) << sol.reason[2];
  EXPECT_NE(sol.reason[3].find("dependent on c"), std::string::npos) << sol.reason[3];
  EXPECT_LT(sol.residual_norm, 1e-12 * b.norm());
  EXPECT_TRUE(std::isfinite(sol.cond));  // over the identifiable columns only
}

TEST(LeastSquaresTest, ConditionNumberOfKnownMatrix) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3, 2);
  A(0, 0) = 10.0;
  A(1, 1) = 0.1;
  const LeastSquaresSolution sol = SolveLeastSquares(A, Eigen::Vector3d(1, 1, 1));
  EXPECT_NEAR(sol.cond, 100.0, 1e-12);          // cond(A), not cond(AᵀA)
  EXPECT_NEAR(sol.cond_normalized, 1.0, 1e-12); // unit-norm columns are orthonormal
  EXPECT_NEAR(sol.x[0], 0.1, 1e-15);
  EXPECT_NEAR(sol.x[1], 10.0, 1e-12);
}

TEST(LeastSquaresTest, RejectsMismatchedSizes) {
  EXPECT_THROW(SolveLeastSquares(Eigen::MatrixXd::Zero(3, 2), Eigen::VectorXd::Zero(4)), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
