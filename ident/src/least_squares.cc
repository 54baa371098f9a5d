#include "idbench/ident/least_squares.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace idbench {
double ConditionNumber(const Eigen::MatrixXd& A) {
  if (A.cols() == 0) return 0.0;
  // A tall matrix has the singular values of its (blocked) QR's R factor.
  if (A.rows() > 2 * A.cols()) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
    const Eigen::MatrixXd R = qr.matrixQR().topRows(A.cols()).triangularView<Eigen::Upper>();
    return ConditionNumber(R);
  }
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  return s[s.size() - 1] > 0.0 ? s[0] / s[s.size() - 1] : std::numeric_limits<double>::infinity();
}

LeastSquaresSolution SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                       const std::vector<std::string>& names,
                                       const LeastSquaresOptions& options) {
  const int n = static_cast<int>(A.cols());
  if (A.rows() != b.size()) {
    throw std::invalid_argument("SolveLeastSquares: A has " + std::to_string(A.rows()) + " rows, b has " +
                                std::to_string(b.size()));
  }
  if (!A.allFinite() || !b.allFinite()) {
    throw std::invalid_argument("SolveLeastSquares: the data contain NaN or Inf");
  }
  auto name = [&](int j) { return j < static_cast<int>(names.size()) ? names[j] : "x" + std::to_string(j); };

  LeastSquaresSolution sol;
  sol.x = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  sol.identifiable.assign(static_cast<size_t>(n), false);
  sol.reason.assign(static_cast<size_t>(n), "");

  // 1. Zero columns: the data do not excite these unknowns at all.
  const Eigen::VectorXd norms = A.colwise().norm();
  const double reference = options.column_norm_reference > 0.0 ? options.column_norm_reference
                                                               : (n > 0 ? norms.maxCoeff() : 0.0);
  std::vector<int> nonzero;
  for (int j = 0; j < n; ++j) {
    if (reference > 0.0 && norms[j] > options.zero_column_tolerance * reference) {
      nonzero.push_back(j);
    } else {
      sol.reason[static_cast<size_t>(j)] = "column of " + name(j) + " is zero: the data do not excite it";
    }
  }
  if (nonzero.empty()) {
    sol.residual_norm = b.norm();
    return sol;
  }

  // 2. SVD of the column-normalised nonzero block.
  const int k = static_cast<int>(nonzero.size());
  Eigen::MatrixXd As(A.rows(), k);
  for (int c = 0; c < k; ++c) As.col(c) = A.col(nonzero[c]) / norms[nonzero[c]];
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(As, Eigen::ComputeThinU | Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  while (rank < s.size() && s[rank] > options.rank_tolerance * s[0]) ++rank;
  sol.rank = rank;

  // 3. An unknown is identifiable iff it has no component in the null space.
  const Eigen::MatrixXd V_null = svd.matrixV().rightCols(k - rank);
  std::vector<int> identified;
  for (int c = 0; c < k; ++c) {
    const int j = nonzero[c];
    if (V_null.rows() == 0 || V_null.row(c).norm() <= 1e-6) {
      sol.identifiable[static_cast<size_t>(j)] = true;
      identified.push_back(j);
      continue;
    }
    std::string partners;
    for (int c2 = 0; c2 < k; ++c2) {
      if (c2 != c && (V_null.row(c2) * V_null.row(c).transpose()).norm() > 1e-6) {
        partners += (partners.empty() ? "" : ", ") + name(nonzero[c2]);
      }
    }
    sol.reason[static_cast<size_t>(j)] =
        "column of " + name(j) + " is linearly dependent" + (partners.empty() ? "" : " on " + partners);
  }

  // 4. Minimum-norm solution; its identifiable entries are unique.
  const Eigen::VectorXd Utb = svd.matrixU().leftCols(rank).transpose() * b;
  const Eigen::VectorXd xs = svd.matrixV().leftCols(rank) * (Utb.array() / s.head(rank).array()).matrix();
  Eigen::VectorXd x_all = Eigen::VectorXd::Zero(n);
  for (int c = 0; c < k; ++c) x_all[nonzero[c]] = xs[c] / norms[nonzero[c]];
  sol.residual_norm = (A * x_all - b).norm();
  for (int j : identified) sol.x[j] = x_all[j];

  // 5. Conditioning of the identifiable block, raw and column-normalised.
  Eigen::MatrixXd Ai(A.rows(), static_cast<int>(identified.size()));
  for (size_t c = 0; c < identified.size(); ++c) Ai.col(static_cast<int>(c)) = A.col(identified[c]);
  sol.cond = ConditionNumber(Ai);
  for (int c = 0; c < Ai.cols(); ++c) Ai.col(c).normalize();
  sol.cond_normalized = ConditionNumber(Ai);
  return sol;
}

}  // namespace idbench
