// Forward-mode automatic differentiation: a value and its derivatives along N
// directions at once. Templated kinematics and regressors run on Dual<N> to
// get exact derivatives with respect to the joint state (no finite
// differences). Comparisons use the value only.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace idbench {

template <int N>
struct Dual {
  using Tangent = Eigen::Matrix<double, N, 1>;
  double v = 0.0;                 // value
  Tangent d = Tangent::Zero();    // derivatives along the N directions

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants convert implicitly
  Dual(double value, const Tangent& tangent) : v(value), d(tangent) {}

  Dual& operator+=(const Dual& o) { v += o.v; d += o.d; return *this; }
  Dual& operator-=(const Dual& o) { v -= o.v; d -= o.d; return *this; }
  Dual& operator*=(const Dual& o) { d = d * o.v + o.d * v; v *= o.v; return *this; }
  Dual& operator/=(const Dual& o) { d = (d - o.d * (v / o.v)) / o.v; v /= o.v; return *this; }
};

// The number of directions carried by the kinematics and regressor derivatives.
inline constexpr int kDualDirections = 6;
using DualState = Dual<kDualDirections>;

template <int N> Dual<N> operator-(const Dual<N>& a) { return {-a.v, -a.d}; }
template <int N> Dual<N> operator+(Dual<N> a, const Dual<N>& b) { return a += b; }
template <int N> Dual<N> operator-(Dual<N> a, const Dual<N>& b) { return a -= b; }
template <int N> Dual<N> operator*(Dual<N> a, const Dual<N>& b) { return a *= b; }
template <int N> Dual<N> operator/(Dual<N> a, const Dual<N>& b) { return a /= b; }
template <int N> Dual<N> operator+(Dual<N> a, double b) { a.v += b; return a; }
template <int N> Dual<N> operator+(double a, Dual<N> b) { b.v += a; return b; }
template <int N> Dual<N> operator-(Dual<N> a, double b) { a.v -= b; return a; }
template <int N> Dual<N> operator-(double a, const Dual<N>& b) { return {a - b.v, -b.d}; }
template <int N> Dual<N> operator*(const Dual<N>& a, double b) { return {a.v * b, a.d * b}; }
template <int N> Dual<N> operator*(double a, const Dual<N>& b) { return {a * b.v, a * b.d}; }
template <int N> Dual<N> operator/(const Dual<N>& a, double b) { return {a.v / b, a.d / b}; }
template <int N> bool operator<(const Dual<N>& a, const Dual<N>& b) { return a.v < b.v; }
template <int N> bool operator>(const Dual<N>& a, const Dual<N>& b) { return a.v > b.v; }
template <int N> bool operator<=(const Dual<N>& a, const Dual<N>& b) { return a.v <= b.v; }
template <int N> bool operator>=(const Dual<N>& a, const Dual<N>& b) { return a.v >= b.v; }
template <int N> bool operator==(const Dual<N>& a, const Dual<N>& b) { return a.v == b.v; }
template <int N> bool operator!=(const Dual<N>& a, const Dual<N>& b) { return a.v != b.v; }

template <int N> Dual<N> sin(const Dual<N>& a) { return {std::sin(a.v), a.d * std::cos(a.v)}; }
template <int N> Dual<N> cos(const Dual<N>& a) { return {std::cos(a.v), a.d * -std::sin(a.v)}; }
template <int N> Dual<N> sqrt(const Dual<N>& a) {
  const double s = std::sqrt(a.v);
  return {s, a.d * (0.5 / s)};
}
template <int N> Dual<N> tanh(const Dual<N>& a) {
  const double t = std::tanh(a.v);
  return {t, a.d * (1.0 - t * t)};
}
template <int N> Dual<N> abs(const Dual<N>& a) { return a.v < 0.0 ? -a : a; }

// Value of a double or a Dual, for code templated on the scalar.
inline double ValueOf(double x) { return x; }
template <int N> double ValueOf(const Dual<N>& x) { return x.v; }

}  // namespace idbench

namespace Eigen {

template <int N>
struct NumTraits<idbench::Dual<N>> : NumTraits<double> {
  using Real = idbench::Dual<N>;
  using NonInteger = idbench::Dual<N>;
  using Nested = idbench::Dual<N>;
  using Literal = idbench::Dual<N>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = N + 1,
    MulCost = 2 * N + 1,
  };
};

template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<idbench::Dual<N>, double, BinaryOp> {
  using ReturnType = idbench::Dual<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, idbench::Dual<N>, BinaryOp> {
  using ReturnType = idbench::Dual<N>;
};

}  // namespace Eigen
