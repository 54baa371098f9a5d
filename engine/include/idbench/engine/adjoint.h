// Reverse-mode automatic differentiation (the adjoint method) on a tape.
// Templated kinematics and regressors run on Adjoint to record every
// elementary operation; one backward sweep then gives the derivatives of one
// output with respect to all inputs at once, for a small multiple of the cost
// of the function itself (forward mode, dual numbers, needs one pass per
// input direction).
//
//   AdjointTape tape;
//   Adjoint x = tape.Input(1.0), y = tape.Input(2.0);
//   Adjoint f = sin(x) * y;
//   tape.Backward(f);               // tape.adjoint(x) = y cos x, tape.adjoint(y) = sin x
//
// Only operations on two recorded values are recorded: constants (plain
// doubles converted to Adjoint) are not, an operation on constants gives a
// constant, and a function of one recorded value (a product with a constant,
// sin, …) reuses its node with the derivative as a scale. Comparisons use the value only
// (so |x| and sign(x) have their one-sided derivatives). A tape is not
// thread-safe; use one per thread. Clear() keeps its capacity, so a reused
// tape does not allocate after warm-up.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace idbench {

class AdjointTape;

#define IDBENCH_ADJOINT_INLINE [[gnu::always_inline]] inline

// A value on the tape: v, and its derivatives are `scale` times those of the
// recorded node (so products with constants, negation and adding constants
// record nothing).
struct Adjoint {
  double v = 0.0;               // value
  double scale = 0.0;           // ∂v/∂(node's value)
  int node = -1;                // index on the tape; −1: a constant
  AdjointTape* tape = nullptr;  // the tape holding node (null for constants)

  Adjoint() = default;
  IDBENCH_ADJOINT_INLINE Adjoint(double value) : v(value) {}  // NOLINT: constants convert implicitly
  IDBENCH_ADJOINT_INLINE Adjoint(double value, double s, int index, AdjointTape* t)
      : v(value), scale(s), node(index), tape(t) {}
  bool constant() const { return node < 0; }
};

class AdjointTape {
 public:
  // One recorded operation: up to two operands (−1: none) and the partial
  // derivatives of its result with respect to their nodes.
  struct Node {
    int a, b;
    double da, db;
  };

  // Forgets every node (keeps the memory).
  void Clear() { size_ = 0; }
  // A new independent variable with value v.
  Adjoint Input(double v) { return {v, 1.0, Push(-1, 0.0, -1, 0.0), this}; }
  // A node with value v and partials da, db with respect to a, b (either may
  // be a constant: its partial is dropped).
  IDBENCH_ADJOINT_INLINE Adjoint Record(double v, const Adjoint& a, double da, const Adjoint& b, double db) {
    return {v, 1.0, Push(a.node, da * a.scale, b.node, db * b.scale), this};
  }

  // ∂output/∂(every node): the backward sweep from output. A constant output
  // gives zero adjoints.
  void Backward(const Adjoint& output) {
    adjoints_.assign(size_, 0.0);
    if (output.constant()) return;
    adjoints_[static_cast<size_t>(output.node)] = output.scale;
    const Node* nodes = nodes_.data();
    double* adjoints = adjoints_.data();
    for (int k = output.node; k >= 0; --k) {
      const double w = adjoints[k];
      const Node& n = nodes[k];
      if (n.a >= 0) adjoints[n.a] += n.da * w;
      if (n.b >= 0) adjoints[n.b] += n.db * w;
    }
  }
  // After Backward: ∂output/∂x (0 for a constant or a node recorded later).
  double adjoint(const Adjoint& x) const {
    return x.constant() || static_cast<size_t>(x.node) >= adjoints_.size()
               ? 0.0
               : x.scale * adjoints_[static_cast<size_t>(x.node)];
  }
  size_t size() const { return size_; }

 private:
  IDBENCH_ADJOINT_INLINE int Push(int a, double da, int b, double db) {
    if (size_ == nodes_.size()) [[unlikely]] nodes_.resize(std::max<size_t>(1024, 2 * nodes_.size()));
    nodes_[size_] = {a, b, da, db};
    return static_cast<int>(size_++);
  }

  std::vector<Node> nodes_;  // the first size_ are recorded
  size_t size_ = 0;
  std::vector<double> adjoints_;
};

namespace internal {
// The tape of a recorded (non-constant) value.
IDBENCH_ADJOINT_INLINE AdjointTape* TapeOf(const Adjoint& a) {
  if (a.tape == nullptr) __builtin_unreachable();
  return a.tape;
}
IDBENCH_ADJOINT_INLINE Adjoint Scaled(const Adjoint& a, double value, double factor) {
  return factor == 0.0 ? Adjoint(value) : Adjoint(value, a.scale * factor, a.node, a.tape);
}
}  // namespace internal

IDBENCH_ADJOINT_INLINE Adjoint operator+(const Adjoint& a, const Adjoint& b) {
  if (b.constant()) return {a.v + b.v, a.scale, a.node, a.tape};
  if (a.constant()) return {a.v + b.v, b.scale, b.node, b.tape};
  return internal::TapeOf(a)->Record(a.v + b.v, a, 1.0, b, 1.0);
}
IDBENCH_ADJOINT_INLINE Adjoint operator-(const Adjoint& a) { return {-a.v, -a.scale, a.node, a.tape}; }
IDBENCH_ADJOINT_INLINE Adjoint operator-(const Adjoint& a, const Adjoint& b) {
  if (b.constant()) return {a.v - b.v, a.scale, a.node, a.tape};
  if (a.constant()) return {a.v - b.v, -b.scale, b.node, b.tape};
  return internal::TapeOf(a)->Record(a.v - b.v, a, 1.0, b, -1.0);
}
IDBENCH_ADJOINT_INLINE Adjoint operator*(const Adjoint& a, const Adjoint& b) {
  if (b.constant()) return a.constant() ? Adjoint(a.v * b.v) : internal::Scaled(a, a.v * b.v, b.v);
  if (a.constant()) return internal::Scaled(b, a.v * b.v, a.v);
  return internal::TapeOf(a)->Record(a.v * b.v, a, b.v, b, a.v);
}
IDBENCH_ADJOINT_INLINE Adjoint operator/(const Adjoint& a, const Adjoint& b) {
  const double r = a.v / b.v;
  if (b.constant()) return a.constant() ? Adjoint(r) : internal::Scaled(a, r, 1.0 / b.v);
  if (a.constant()) return internal::Scaled(b, r, -r / b.v);
  return internal::TapeOf(a)->Record(r, a, 1.0 / b.v, b, -r / b.v);
}
// Mixed with double.
IDBENCH_ADJOINT_INLINE Adjoint operator*(const Adjoint& a, double b) { return a * Adjoint(b); }
IDBENCH_ADJOINT_INLINE Adjoint operator*(double a, const Adjoint& b) { return Adjoint(a) * b; }
IDBENCH_ADJOINT_INLINE Adjoint operator+(const Adjoint& a, double b) { return a + Adjoint(b); }
IDBENCH_ADJOINT_INLINE Adjoint operator+(double a, const Adjoint& b) { return Adjoint(a) + b; }
IDBENCH_ADJOINT_INLINE Adjoint operator-(const Adjoint& a, double b) { return a - Adjoint(b); }
IDBENCH_ADJOINT_INLINE Adjoint operator-(double a, const Adjoint& b) { return Adjoint(a) - b; }
IDBENCH_ADJOINT_INLINE Adjoint operator/(const Adjoint& a, double b) { return a / Adjoint(b); }

IDBENCH_ADJOINT_INLINE Adjoint& operator+=(Adjoint& a, const Adjoint& b) { return a = a + b; }
IDBENCH_ADJOINT_INLINE Adjoint& operator-=(Adjoint& a, const Adjoint& b) { return a = a - b; }
IDBENCH_ADJOINT_INLINE Adjoint& operator*=(Adjoint& a, const Adjoint& b) { return a = a * b; }
IDBENCH_ADJOINT_INLINE Adjoint& operator/=(Adjoint& a, const Adjoint& b) { return a = a / b; }

inline bool operator<(const Adjoint& a, const Adjoint& b) { return a.v < b.v; }
inline bool operator>(const Adjoint& a, const Adjoint& b) { return a.v > b.v; }
inline bool operator<=(const Adjoint& a, const Adjoint& b) { return a.v <= b.v; }
inline bool operator>=(const Adjoint& a, const Adjoint& b) { return a.v >= b.v; }
inline bool operator==(const Adjoint& a, const Adjoint& b) { return a.v == b.v; }
inline bool operator!=(const Adjoint& a, const Adjoint& b) { return a.v != b.v; }

inline Adjoint sin(const Adjoint& a) { return internal::Scaled(a, std::sin(a.v), std::cos(a.v)); }
inline Adjoint cos(const Adjoint& a) { return internal::Scaled(a, std::cos(a.v), -std::sin(a.v)); }
inline Adjoint sqrt(const Adjoint& a) {
  const double s = std::sqrt(a.v);
  return internal::Scaled(a, s, 0.5 / s);
}
inline Adjoint tanh(const Adjoint& a) {
  const double t = std::tanh(a.v);
  return internal::Scaled(a, t, 1.0 - t * t);
}
inline Adjoint abs(const Adjoint& a) { return a.v < 0.0 ? -a : a; }

#undef IDBENCH_ADJOINT_INLINE

// Value of a double or an Adjoint, for code templated on the scalar.
inline double ValueOf(double x) { return x; }
inline double ValueOf(const Adjoint& x) { return x.v; }

}  // namespace idbench

namespace Eigen {

template <>
struct NumTraits<idbench::Adjoint> : NumTraits<double> {
  using Real = idbench::Adjoint;
  using NonInteger = idbench::Adjoint;
  using Nested = idbench::Adjoint;
  using Literal = idbench::Adjoint;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 3,
    MulCost = 3,
  };
};

template <typename BinaryOp>
struct ScalarBinaryOpTraits<idbench::Adjoint, double, BinaryOp> {
  using ReturnType = idbench::Adjoint;
};
template <typename BinaryOp>
struct ScalarBinaryOpTraits<double, idbench::Adjoint, BinaryOp> {
  using ReturnType = idbench::Adjoint;
};

}  // namespace Eigen
