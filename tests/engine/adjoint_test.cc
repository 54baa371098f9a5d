#include "idbench/engine/adjoint.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/test_robots.h"
#include "engine/test_util.h"
#include "idbench/engine/kinematics.h"

namespace idbench {
namespace {

// f(x, y) = sin(x)·y/(1 + x²) − cos(y)·3 + tanh(x − y) + √(x² + y²) against its
// derivatives written out by hand.
TEST(AdjointTest, ElementaryOperationsMatchAnalyticDerivatives) {
  AdjointTape tape;
  for (const auto& [x0, y0] : {std::pair{0.3, -1.2}, std::pair{-2.0, 0.7}, std::pair{1.5, 2.5}}) {
    tape.Clear();
    const Adjoint x = tape.Input(x0), y = tape.Input(y0);
    const Adjoint f = sin(x) * y / (1.0 + x * x) - cos(y) * 3.0 + tanh(x - y) + sqrt(x * x + y * y);
    tape.Backward(f);
    const double r = std::hypot(x0, y0), t = std::tanh(x0 - y0), d = 1.0 + x0 * x0;
    const double fx = std::cos(x0) * y0 / d - std::sin(x0) * y0 * 2.0 * x0 / (d * d) + (1.0 - t * t) + x0 / r;
    const double fy = std::sin(x0) / d + 3.0 * std::sin(y0) - (1.0 - t * t) + y0 / r;
    EXPECT_NEAR(f.v, std::sin(x0) * y0 / d - 3.0 * std::cos(y0) + t + r, 1e-15);
    EXPECT_NEAR(tape.adjoint(x), fx, 1e-14 * std::abs(fx) + 1e-15);
    EXPECT_NEAR(tape.adjoint(y), fy, 1e-14 * std::abs(fy) + 1e-15);
  }
}

// Constants are not recorded, a product with a constant reuses its operand's
// node, and a zero factor gives a constant.
TEST(AdjointTest, ConstantsAreNotRecorded) {
  AdjointTape tape;
  const Adjoint x = tape.Input(2.0);
  const Adjoint c = Adjoint(3.0) * Adjoint(4.0) + 1.0;
  EXPECT_TRUE(c.constant());
  const Adjoint y = -(5.0 * x) + c;  // −5x + 13
  EXPECT_EQ(tape.size(), 1u);
  EXPECT_TRUE((0.0 * x).constant());
  tape.Backward(y);
  EXPECT_DOUBLE_EQ(tape.adjoint(x), -5.0);
  EXPECT_DOUBLE_EQ(y.v, 3.0);
}

// The centre-of-mass acceleration of the last link, contracted with a fixed
// vector, differentiated with respect to (q, qd, qdd) by one backward sweep,
// against central differences of the double kinematics (h = 1e-6: truncation
// ~h², rounding ~ε/h; tolerance 1e-7 relative).
TEST(AdjointTest, KinematicsGradientMatchesFiniteDifferences) {
  const RobotModel model = testing::MakeTestRobot(2);
  const int n = model.n_dof();
  std::mt19937 rng(5);
  const Eigen::VectorXd q = testing::RandomVector(n, 2.0, &rng), qd = testing::RandomVector(n, 1.5, &rng),
                        qdd = testing::RandomVector(n, 3.0, &rng);
  const Eigen::Vector3d weight(0.3, -0.8, 0.5);
  const size_t last = static_cast<size_t>(model.n_links() - 1);
  auto f = [&](const Eigen::VectorXd& x) {
    KinematicsData<double> k(model);
    ComputeKinematicsT<double>(model, x.head(n), x.segment(n, n), x.tail(n), &k);
    return weight.dot(k.a_WBcm_W[last]);
  };
  AdjointTape tape;
  KinematicsData<Adjoint> k(model);
  Eigen::Matrix<Adjoint, Eigen::Dynamic, 1> aq(n), aqd(n), aqdd(n);
  for (int j = 0; j < n; ++j) aq[j] = tape.Input(q[j]);
  for (int j = 0; j < n; ++j) aqd[j] = tape.Input(qd[j]);
  for (int j = 0; j < n; ++j) aqdd[j] = tape.Input(qdd[j]);
  ComputeKinematicsT<Adjoint>(model, aq, aqd, aqdd, &k);
  const Adjoint out = k.a_WBcm_W[last].x() * weight.x() + k.a_WBcm_W[last].y() * weight.y() +
                      k.a_WBcm_W[last].z() * weight.z();
  tape.Backward(out);
  Eigen::VectorXd x(3 * n), g(3 * n), fd(3 * n);
  x << q, qd, qdd;
  EXPECT_NEAR(out.v, f(x), 1e-12);
  for (int i = 0; i < 3 * n; ++i) {
    const Adjoint& input = i < n ? aq[i] : i < 2 * n ? aqd[i - n] : aqdd[i - 2 * n];
    g[i] = tape.adjoint(input);
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += 1e-6;
    xm[i] -= 1e-6;
    fd[i] = (f(xp) - f(xm)) / 2e-6;
  }
  EXPECT_LT((g - fd).norm(), 1e-7 * fd.norm()) << "adjoint " << g.transpose() << "\nfd " << fd.transpose();
}

}  // namespace
}  // namespace idbench
